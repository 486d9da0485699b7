// Subcommands of the headless front end `ehd_sim`.
//
// Each src/cli/<name>_command.cpp defines one subcommand and registers it with a static
// CommandRegistration; main() dispatches on the first argument. A subcommand receives its own
// arguments (without the subcommand name) and returns the process exit code. It reports bad
// options by throwing UsageError, which main() prints with the subcommand's usage.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace ehd::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Command {
  std::string name;
  std::string summary;  // one line for `ehd_sim --help`
  std::string usage;    // full usage for `ehd_sim NAME --help`
  std::function<int(const std::vector<std::string>& args)> run;
};

std::map<std::string, Command>& CommandTable();

struct CommandRegistration {
  explicit CommandRegistration(Command command) {
    CommandTable().emplace(command.name, std::move(command));
  }
};

// Small helpers shared by the subcommands' option parsers.
// Parses "a,b,c" into integers; throws UsageError naming the option on bad input.
std::vector<int> ParseIntList(const std::string& option, const std::string& text);
// A finite number (nan and inf are refused).
double ParseDouble(const std::string& option, const std::string& text);
long ParseLong(const std::string& option, const std::string& text);
// A number in (lo, hi] (lo_open) or [lo, hi]; the error names the option, `what` ("a time"),
// the range and `note` (" (as numerics.t_end)").
double ParseDoubleIn(const std::string& option, const std::string& text, double lo, double hi,
                     bool lo_open, const std::string& what, const std::string& note = "");
// An integer in [lo, hi].
long ParseLongIn(const std::string& option, const std::string& text, long lo, long hi);
// Returns args[i+1] for an option that takes a value, or throws UsageError.
const std::string& OptionValue(const std::vector<std::string>& args, std::size_t& i);
// The same for a file or directory: an empty path is refused.
const std::string& PathValue(const std::vector<std::string>& args, std::size_t& i);

}  // namespace ehd::cli
