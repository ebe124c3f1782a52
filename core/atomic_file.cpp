#include "core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/errors.hpp"

namespace terracal {

namespace fs = std::filesystem;

std::string temporary_path_for(const std::string& final_path) {
  const fs::path p(final_path);
  const std::string name = p.filename().string();
  if (name.empty()) throw RunError("cannot write '" + final_path + "': the path names a folder, not a file");
  const std::string tmp_name = "." + name + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  return (p.parent_path() / tmp_name).string();
}

void commit_file(const std::string& tmp, const std::string& final_path) {
  std::error_code ec;
  fs::rename(tmp, final_path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);  // do not leave the temporary behind either
    throw RunError("cannot move '" + tmp + "' to '" + final_path + "': " + ec.message());
  }
}

void write_text_atomically(const std::string& path, std::string_view content) {
  const std::string tmp = temporary_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      const int err = errno;
      throw RunError("cannot write '" + path + "': cannot create '" + tmp + "': " + std::strerror(err));
    }
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();  // close explicitly: a full disk often shows up only when the buffer is flushed
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw RunError("cannot write '" + path + "': writing '" + tmp + "' failed");
    }
  }
  commit_file(tmp, path);
}

}  // namespace terracal
