#include "apps/out_dir.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::app {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& path, const std::string& why) {
  throw InputError(fmt::format("{} {}: {}; expected a folder that can be written, or made in one", option, path, why));
}

// Writes and removes a file in `dir`: permissions alone do not say (root ignores them; /proc and
// read-only file systems refuse whatever the bits say). Returns "" or the reason.
std::string probe_write(const fs::path& dir) {
  std::string name = (dir / ".terracal_out_probe_XXXXXX").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) return fmt::format("cannot write in the folder ({})", std::strerror(errno));
  ::close(fd);
  ::unlink(name.c_str());
  return "";
}

}  // namespace

OutDir::OutDir(const std::string& option, const std::string& path)
    : path_(path), exceptions_(std::uncaught_exceptions()) {
  if (path.empty()) refuse(option, "''", "an empty path");
  std::error_code ec;
  fs::path p = fs::absolute(path, ec).lexically_normal();
  if (ec) refuse(option, path, ec.message());
  if (p.filename().empty()) p = p.parent_path();  // "out/" is "out"
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) refuse(option, path, "exists and is not a folder");
    if (const std::string why = probe_write(p); !why.empty()) refuse(option, path, why);
    for (const auto& name : remove_stale_temporaries(p.string()))
      spdlog::info("removed {}, left in {} by an interrupted write", name, path);
    return;
  }
  // The nearest folder above that exists, and the first of the path's folders below it.
  fs::path above = p, missing;
  while (!fs::exists(above, ec) && above.has_relative_path()) {
    missing = above;
    above = above.parent_path();
  }
  if (!fs::is_directory(above, ec)) refuse(option, path, fmt::format("{} is not a folder", above.string()));
  if (!fs::create_directory(missing, ec))
    refuse(option, path, fmt::format("cannot make the folder {} ({})", missing.string(), ec.message()));
  const std::string why = probe_write(missing);
  fs::remove(missing, ec);
  if (!why.empty()) refuse(option, path, why);
  first_missing_ = missing.string();
}

OutDir::~OutDir() {
  if (first_missing_.empty() || std::uncaught_exceptions() <= exceptions_) return;
  std::error_code ec;
  fs::path p = fs::absolute(path_, ec).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  const fs::path stop = first_missing_;
  // Innermost first: each folder goes only when empty, so no output is ever removed.
  while (!ec && p.has_relative_path()) {
    if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) return;
    if (p == stop) return;
    p = p.parent_path();
  }
}

}  // namespace terracal::app
