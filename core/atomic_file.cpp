#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/errors.hpp"

namespace terracal {

namespace fs = std::filesystem;

namespace {

// fsync of a file or a folder by path; "" on success, else the reason.
std::string sync_path(const std::string& path, bool folder) {
  const int fd = ::open(path.c_str(), (folder ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::strerror(errno);
  std::string err;
  // EINVAL: the file system cannot sync (some pseudo and network file systems); nothing more to do.
  if (::fsync(fd) != 0 && errno != EINVAL) err = std::strerror(errno);
  ::close(fd);
  return err;
}

// The PID of a temporary's name `.NAME.tmp.PID`, or 0 when `name` is not one.
long temporary_pid(const std::string& name) {
  const auto at = name.rfind(".tmp.");
  if (name.empty() || name[0] != '.' || at == std::string::npos || at == 0) return 0;
  const char* first = name.data() + at + 5;
  const char* last = name.data() + name.size();
  long pid = 0;
  const auto [ptr, ec] = std::from_chars(first, last, pid);
  return ec == std::errc() && ptr == last && pid > 0 ? pid : 0;
}

bool process_running(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }

}  // namespace

std::string temporary_path_for(const std::string& final_path) {
  const fs::path p(final_path);
  const std::string name = p.filename().string();
  if (name.empty()) throw RunError("cannot write '" + final_path + "': the path names a folder, not a file");
  const std::string tmp_name = "." + name + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  return (p.parent_path() / tmp_name).string();
}

void commit_file(const std::string& tmp, const std::string& final_path) {
  std::error_code ec;
  std::string why = sync_path(tmp, false);
  if (why.empty()) {
    fs::rename(tmp, final_path, ec);
    if (ec) why = ec.message();
  }
  if (!why.empty()) {
    std::error_code ignored;
    fs::remove(tmp, ignored);  // do not leave the temporary behind either
    throw RunError("cannot move '" + tmp + "' to '" + final_path + "': " + why);
  }
  const fs::path folder = fs::path(final_path).parent_path();
  why = sync_path(folder.empty() ? std::string(".") : folder.string(), true);
  if (!why.empty()) throw RunError("wrote '" + final_path + "' but cannot flush its folder to disk: " + why);
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

std::vector<std::string> remove_stale_temporaries(const std::string& dir) {
  std::vector<std::string> removed;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const long pid = temporary_pid(it->path().filename().string());
    if (pid == 0 || pid == static_cast<long>(::getpid()) || process_running(pid)) continue;
    std::error_code rm;
    if (it->is_regular_file(rm) && fs::remove(it->path(), rm))
      removed.push_back(it->path().lexically_relative(dir).string());
  }
  return removed;
}

}  // namespace terracal
