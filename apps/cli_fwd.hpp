#pragma once
// CLI11's classes by name only, for headers that pass them around. <CLI/CLI.hpp> defines global
// validators and costs several seconds of compile time in every file that includes it, so only the
// files that build command lines include it.
namespace CLI {
class App;
class Option;
class Validator;
}  // namespace CLI
