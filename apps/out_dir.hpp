#pragma once
// A command's output folder (--out): checked before any work starts, and never left behind empty by
// a run that fails. Every command that has --out holds one while it runs.
#include <string>

namespace terracal::app {

class OutDir {
 public:
  // Checks that `path` is a folder this process can write in, or one it can make (the nearest
  // folder above it that exists takes a new folder); throws InputError "OPTION PATH: why; expected
  // ..." otherwise. Leaves nothing behind: a probe file or folder is removed again at once. The
  // command makes the folder itself once its inputs are checked.
  OutDir(const std::string& option, const std::string& path);
  // When the command ends by an exception (a refusal, exit 2, or a failed run, exit 1), the folders
  // of the path that did not exist at the check and are still empty are removed.
  ~OutDir();
  OutDir(const OutDir&) = delete;
  OutDir& operator=(const OutDir&) = delete;

 private:
  std::string path_;
  std::string first_missing_;  // the outermost folder of the path that did not exist ("": it existed)
  int exceptions_ = 0;         // std::uncaught_exceptions() at the check
};

// The one check of every command's output folder option (see OutDir).
inline OutDir prepare_out_dir(const std::string& option, const std::string& path) { return OutDir(option, path); }

}  // namespace terracal::app
