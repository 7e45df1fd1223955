#pragma once
// Shared by every ffr executable: a small argument parser, --help/--version, and run_main(),
// which maps exceptions to the exit codes of docs/contract.md:
//   bad input (ffr::formats::FormatError, std::invalid_argument, ffr::cli::UsageError) -> 2,
//   anything else -> 1; each with one line "<tool>: error: <message>" on stderr.

#include "ffr/formats/h5.hpp"
#include "ffr/version.hpp"

#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::cli {

/// A command-line mistake (unknown option, missing value): bad input, exit status 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct Command {
  std::string name;   ///< e.g. "ffr-info"
  std::string usage;  ///< full --help text after the "usage:" line
  std::string synopsis;
};

/// Arguments after argv[0]. Options are "--name value" or "--name=value"; flags "--name".
class Args {
 public:
  explicit Args(std::vector<std::string> a) : args_(std::move(a)), used_(args_.size(), false) {}

  /// True if the flag is present (and consumes it).
  bool flag(const std::string& name) {
    bool found = false;
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (!used_[i] && args_[i] == name) used_[i] = found = true;
    return found;
  }

  /// The value of an option, if given (the last occurrence wins).
  std::optional<std::string> option(const std::string& name) {
    std::optional<std::string> v;
    for (std::size_t i = 0; i < args_.size(); ++i) {
      if (used_[i]) continue;
      if (args_[i] == name) {
        if (i + 1 >= args_.size()) throw UsageError("option " + name + " needs a value");
        used_[i] = used_[i + 1] = true;
        v = args_[++i];
      } else if (args_[i].rfind(name + "=", 0) == 0) {
        used_[i] = true;
        v = args_[i].substr(name.size() + 1);
      }
    }
    return v;
  }

  std::optional<double> number(const std::string& name) {
    auto v = option(name);
    if (!v) return std::nullopt;
    return parse_double(*v, name);
  }

  /// Everything not consumed; an unknown "--option" is a usage error.
  std::vector<std::string> positionals() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < args_.size(); ++i) {
      if (used_[i]) continue;
      if (args_[i].size() > 1 && args_[i][0] == '-' && !is_number(args_[i]))
        throw UsageError("unknown option " + args_[i]);
      out.push_back(args_[i]);
    }
    return out;
  }

  static bool is_number(const std::string& s) {
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return !s.empty() && end && *end == '\0';
  }

  static double parse_double(const std::string& s, const std::string& what) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || !end || *end != '\0' || !std::isfinite(v))
      throw UsageError(what + ": expected a finite number, got '" + s + "'");
    return v;
  }

  /// "0,50,100" -> {0, 50, 100}.
  static std::vector<double> parse_list(const std::string& s, const std::string& what) {
    std::vector<double> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(parse_double(item, what));
    if (out.empty()) throw UsageError(what + ": expected a comma-separated list of numbers");
    return out;
  }

 private:
  std::vector<std::string> args_;
  std::vector<bool> used_;
};

/// Runs fn with the arguments, after answering --help and --version. Never throws.
inline int run_main(int argc, char** argv, const Command& cmd, const std::function<int(Args&)>& fn) {
  std::vector<std::string> a(argv + 1, argv + argc);
  for (const auto& s : a) {
    if (s == "--help" || s == "-h") {
      std::cout << "usage: " << cmd.synopsis << "\n" << cmd.usage;
      return 0;
    }
    if (s == "--version") {
      std::cout << cmd.name << " (" << ffr::kGenerator << ")\n";
      return 0;
    }
  }
  try {
    Args args(std::move(a));
    return fn(args);
  } catch (const UsageError& e) {
    std::cerr << cmd.name << ": error: " << e.what() << " (see " << cmd.name << " --help)\n";
    return 2;
  } catch (const ffr::formats::FormatError& e) {
    std::cerr << cmd.name << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << cmd.name << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << cmd.name << ": error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << cmd.name << ": error: unknown failure\n";
    return 1;
  }
}

}  // namespace ffr::cli
