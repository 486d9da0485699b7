// ehd_sim: the headless front end of the ehd_capsule simulator (no ROS needed).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "command.h"
#include "ehd_capsule/lbm/openmp_wait.h"
#include "ehd_capsule/version.h"

namespace ehd::cli {

std::map<std::string, Command>& CommandTable() {
  static std::map<std::string, Command> table;
  return table;
}

std::vector<int> ParseIntList(const std::string& option, const std::string& text) {
  std::vector<int> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = text.find(',', pos);
    const std::string item =
        text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    out.push_back(static_cast<int>(ParseLong(option, item)));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

namespace {

// The number in text (nan and inf included), or nullopt.
std::optional<double> NumberIn(const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

std::string Format(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

double ParseDouble(const std::string& option, const std::string& text) {
  const std::optional<double> v = NumberIn(text);
  if (!v || !std::isfinite(*v)) {
    throw UsageError(option + ": expected a finite number, got '" + text + "'");
  }
  return *v;
}

double ParseDoubleIn(const std::string& option, const std::string& text, double lo, double hi,
                     bool lo_open, const std::string& what, const std::string& note) {
  const std::optional<double> v = NumberIn(text);
  // NaN fails both comparisons.
  if (!v || !(lo_open ? *v > lo : *v >= lo) || !(*v <= hi)) {
    throw UsageError(option + " must be " + what + " in " + (lo_open ? "(" : "[") + Format(lo) +
                     ", " + Format(hi) + "]" + note + ", got '" + text + "'");
  }
  return *v;
}

long ParseLongIn(const std::string& option, const std::string& text, long lo, long hi) {
  const long v = ParseLong(option, text);
  if (v < lo || v > hi) {
    throw UsageError(option + " must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "], got '" + text + "'");
  }
  return v;
}

long ParseLong(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const long v = std::stol(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
    return v;
  } catch (const std::exception&) {
    throw UsageError(option + ": expected an integer, got '" + text + "'");
  }
}

const std::string& OptionValue(const std::vector<std::string>& args, std::size_t& i) {
  if (i + 1 >= args.size()) throw UsageError(args[i] + " needs a value");
  return args[++i];
}

const std::string& PathValue(const std::vector<std::string>& args, std::size_t& i) {
  const std::string& path = OptionValue(args, i);
  if (path.empty()) throw UsageError(args[i - 1] + " needs a path, got an empty one");
  return path;
}

namespace {

void PrintUsage(std::ostream& out) {
  out << "usage: ehd_sim <command> [options]\n"
         "       ehd_sim <command> --help\n"
         "       ehd_sim --help | --version\n\n"
         "Headless electrohydrodynamics of capsules, drops and red blood cells in shear flow\n"
         "under a DC electric field (lattice Boltzmann + immersed boundary + fast IIM).\n\n"
         "commands:\n";
  for (const auto& [name, command] : CommandTable()) {
    out << "  " << name;
    for (std::size_t pad = name.size(); pad < 12; ++pad) out << ' ';
    out << command.summary << '\n';
  }
}

}  // namespace
}  // namespace ehd::cli

int main(int argc, char** argv) {
  ehd::RestartWithPassiveOpenMpWait(argv);  // lbm/openmp_wait.h
  using namespace ehd::cli;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    PrintUsage(std::cerr);
    return 2;
  }
  const std::string& first = args.front();
  if (first == "--help" || first == "-h" || first == "help") {
    PrintUsage(std::cout);
    return 0;
  }
  if (first == "--version" || first == "-V") {
    std::cout << "ehd_sim " << ehd::kVersion << '\n';
    return 0;
  }
  if (!first.empty() && first[0] == '-') {
    std::cerr << "ehd_sim: unknown option '" << first << "'\n\n";
    PrintUsage(std::cerr);
    return 2;
  }
  auto it = CommandTable().find(first);
  if (it == CommandTable().end()) {
    std::cerr << "ehd_sim: unknown command '" << first << "' (see ehd_sim --help)\n";
    return 2;
  }
  const Command& command = it->second;
  std::vector<std::string> rest(args.begin() + 1, args.end());
  for (const auto& a : rest) {
    if (a == "--help" || a == "-h") {
      std::cout << command.usage;
      return 0;
    }
  }
  try {
    return command.run(rest);
  } catch (const UsageError& e) {
    std::cerr << "ehd_sim " << command.name << ": " << e.what() << "\n\n" << command.usage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ehd_sim " << command.name << ": error: " << e.what() << '\n';
    return 1;
  }
}
