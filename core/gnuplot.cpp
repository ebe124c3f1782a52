#include "core/gnuplot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/errors.hpp"

namespace terracal {

namespace fs = std::filesystem;

namespace {

// Full path of the gnuplot executable, or "" when PATH has none.
std::string find_gnuplot() {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) folder = ".";  // an empty PATH entry means the current folder
    const fs::path candidate = fs::path(folder) / "gnuplot";
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

const std::string& gnuplot_path() {
  static const std::string path = find_gnuplot();  // thread-safe one-time lookup
  return path;
}

// Single-quoted for /bin/sh: safe for any folder name, including spaces and quotes.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string tail_of_file(const fs::path& p, std::size_t max_chars) {
  std::ifstream in(p, std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (text.size() > max_chars) text = "..." + text.substr(text.size() - max_chars);
  return text;
}

}  // namespace

bool gnuplot_available() { return !gnuplot_path().empty(); }

void run_gnuplot(const std::string& script, const std::string& workdir) {
  if (!gnuplot_available()) throw RunError("plotting: gnuplot was not found on PATH");
  const fs::path dir(workdir);
  const fs::path script_file = dir / "plot.gp";
  const fs::path log_file = dir / "gnuplot.log";
  {
    std::ofstream out(script_file, std::ios::binary | std::ios::trunc);
    out << script;
    out.close();
    if (!out) throw RunError("plotting: cannot write the gnuplot script '" + script_file.string() + "'");
  }
  // Run inside workdir so the script's relative data-file names resolve there; gnuplot's stdout
  // and stderr both go to the log, which becomes the error message if it fails.
  const std::string command =
      "cd " + shell_quote(dir.string()) + " && " + shell_quote(gnuplot_path()) + " plot.gp > gnuplot.log 2>&1";
  const int status = std::system(command.c_str());
  if (status == -1) throw RunError("plotting: cannot start a shell to run gnuplot");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string why =
        WIFEXITED(status) ? "exited with status " + std::to_string(WEXITSTATUS(status)) : "was killed by a signal";
    throw RunError("plotting: gnuplot " + why + " running '" + script_file.string() +
                   "': " + tail_of_file(log_file, 2000));
  }
}

}  // namespace terracal
