#pragma once
// What every maker of jobs (campaign, study) does with a spec's options: options for a terracal
// command given in JSON (name without dashes -> value) are checked by that command's own CLI
// definition (its ranges and choices) before any job starts, and turned into command-line words.
// Also the spec-reading helpers they share: files relative to the spec, unknown keys.
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace terracal::app {

// Throws InputError "<spec>: key '<where><name>': ..." for an option `command` does not take, one in
// `reserved` (the maker sets it itself), a flag whose value is not true/false, or a value the option
// refuses.
void check_command_options(const std::string& spec, const std::string& where, const std::string& command,
                           const nlohmann::ordered_json& options, const std::set<std::string>& reserved);

// The words of `options` on `command`'s command line: "--name value...", a flag given true as "--name"
// (false: left out). A list is one word per element where the option takes several values (--gravity X
// Y Z), else joined by commas (--slips 0.1,0.3).
std::vector<std::string> command_option_words(const std::string& command, const nlohmann::ordered_json& options);

// A file named in the spec, relative to the spec's folder, made absolute; throws InputError when it is
// not a non-empty string or no such file exists.
std::string spec_file(const std::string& spec, const std::string& key, const nlohmann::ordered_json& v);

// Throws InputError naming the first key of `o` not in `ok`.
void refuse_unknown(const std::string& spec, const std::string& where, const nlohmann::ordered_json& o,
                    const std::set<std::string>& ok);

}  // namespace terracal::app
