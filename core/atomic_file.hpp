#pragma once
// Writing output files so that a failed or interrupted command never leaves a partial file under
// its final name, and a finished one survives a power cut: write everything to a temporary name in
// the same folder, flush it to disk (fsync), rename it over the final name, then flush the folder
// so that the rename itself is on disk. A rename within one file system replaces the target
// atomically, so a reader sees either the old file or the complete new one; a crash leaves at most
// a hidden `.name.tmp.PID` file behind, which the next run in that folder removes.
#include <string>
#include <string_view>
#include <vector>

namespace terracal {

// `dir/.name.tmp.<pid>` for `dir/name`: same folder (so the rename stays on one file system),
// hidden, and distinct per process so two commands writing the same output do not collide.
std::string temporary_path_for(const std::string& final_path);

// The one way every output reaches its final name: fsyncs `tmp`, renames it to `final_path`
// (replacing any existing file) and fsyncs the folder. On failure removes `tmp` and throws
// RunError naming both paths; the final name is then untouched.
void commit_file(const std::string& tmp, const std::string& final_path);

// Writes `content` to a temporary file and commits it. Throws RunError (and leaves no file under
// either name) when the folder does not exist or the write fails.
void write_text_atomically(const std::string& path, std::string_view content);

// Removes the temporaries (`.NAME.tmp.PID`) that interrupted writes left in `dir` and its subfolders,
// skipping those of processes still running (another command may be writing there right now).
// Returns their paths relative to `dir`, for the log.
std::vector<std::string> remove_stale_temporaries(const std::string& dir);

}  // namespace terracal
