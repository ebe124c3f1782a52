#pragma once
// Writing output files so that a failed or interrupted command never leaves a partial file under
// its final name: write everything to a temporary name in the same folder, then rename. A rename
// within one file system replaces the target atomically, so a reader sees either the old file or
// the complete new one; a crash leaves at most a hidden `.name.tmp.PID` file behind.
#include <string>
#include <string_view>

namespace terracal {

// `dir/.name.tmp.<pid>` for `dir/name`: same folder (so the rename stays on one file system),
// hidden, and distinct per process so two commands writing the same output do not collide.
std::string temporary_path_for(const std::string& final_path);

// Renames `tmp` to `final_path`, replacing any existing file. On failure removes `tmp` and throws
// RunError naming both paths; the final name is then untouched.
void commit_file(const std::string& tmp, const std::string& final_path);

// Writes `content` to a temporary file and commits it. Throws RunError (and leaves no file under
// either name) when the folder does not exist or the write fails.
void write_text_atomically(const std::string& path, std::string_view content);

}  // namespace terracal
