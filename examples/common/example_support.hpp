#pragma once
// Command line, stdout and figure helpers shared by every example binary.
//
// Every example takes `--out DIR` (default: current directory), writes
// DIR/<name>.csv, then DIR/<name>.png when gnuplot is on the PATH, and prints
// its designed gains and final estimates as `name = value` lines.

#include <adaptobs/core/validation.hpp>
#include <adaptobs/simulation/output_loss.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace adaptobs::examples {

/// A number as a reader writes it: 300, 0.01, 1e5, 1e-5.
[[nodiscard]] inline std::string format_number(double x) {
  std::ostringstream os;
  if (std::abs(x) >= 1e5) os << std::scientific;
  os << x;
  std::string text = os.str();  // 1.000000e+05, 1e-05
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  const bool negative = text[e + 1] == '-';
  return mantissa + (negative ? "e-" : "e") + text.substr(text.find_first_not_of("+-0", e + 1));
}

/// The finite number that is all of `text` (a leading '+' allowed), or nothing.
[[nodiscard]] inline std::optional<double> parse_number(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-') text.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// "T0,T1" with 0 <= T0 <= T1, as {T0, T1}, or nothing.
[[nodiscard]] inline std::optional<std::pair<double, double>> parse_interval(std::string_view text) {
  const auto comma = text.find(',');
  if (comma == std::string_view::npos) return std::nullopt;
  const auto begin = parse_number(text.substr(0, comma)), end = parse_number(text.substr(comma + 1));
  if (!begin || !end || *begin < 0 || *begin > *end) return std::nullopt;
  return std::pair{*begin, *end};
}

/// The values a flag accepts: `test` tells them, `range` says them ("in [0, 1)").
struct Accepts {
  std::string range;
  std::function<bool(std::string_view)> test;
};

/// Numbers from `low` to `high`; `ends` says which ends belong: "[]", "[)", "(]" or "()".
[[nodiscard]] inline Accepts real_in(double low, double high, std::string_view ends = "[]") {
  const bool low_open = ends[0] == '(', high_open = ends[1] == ')';
  return {"in " + std::string(1, ends[0]) + format_number(low) + ", " + format_number(high) + std::string(1, ends[1]),
          [=](std::string_view text) {
            const auto x = parse_number(text);
            return x && (low_open ? *x > low : *x >= low) && (high_open ? *x < high : *x <= high);
          }};
}

/// Whole numbers from `low` to `high` (1e5 is one, 1.5 is not).
[[nodiscard]] inline Accepts integer_in(double low, double high) {
  return {"an integer in [" + format_number(low) + ", " + format_number(high) + "]", [=](std::string_view text) {
            const auto x = parse_number(text);
            return x && *x == std::floor(*x) && *x >= low && *x <= high;
          }};
}

/// An interval of time "T0,T1" with 0 <= T0 <= T1, or "none".
[[nodiscard]] inline Accepts interval_or_none() {
  return {"none or T0,T1 with 0 <= T0 <= T1",
          [](std::string_view text) { return text == "none" || parse_interval(text).has_value(); }};
}

/// One `--name value` flag of an example, or a switch (`--name` alone).
struct Option {
  std::string name;         ///< the flag without "--"
  std::string value;        ///< its default; "off" makes it a switch, which the flag alone turns "on"
  std::string description;  ///< what it sets
  std::string unit;         ///< its unit, "" for a pure number
  Accepts accepts;          ///< its valid values (none for a switch)
};

/// A switch: off unless given.
[[nodiscard]] inline Option toggle(std::string name, std::string description) {
  return {std::move(name), "off", std::move(description), "", {}};
}

/// The flags of an example, each declared once with its default, description,
/// unit and valid values, and `--out DIR` (default: the current directory).
/// Every value is checked, and `--out` created and probed with a file, before
/// the example does any work: a bad value ends the program with one line on
/// stderr that names the flag and its valid values, and exit code 2. `--help`
/// prints every flag with its default, unit and range. A check that depends on
/// several flags is the example's, through `require`.
class Arguments {
 public:
  Arguments(int argc, char** argv, std::string_view program, std::vector<Option> options)
      : program_(program), options_(std::move(options)) {
    options_.insert(options_.begin(), Option{"out",
                                             ".",
                                             "folder of the CSV files and figures, created when missing",
                                             "",
                                             {"a writable directory", nullptr}});
    for (const Option& option : options_) values_[option.name] = option.value;
    for (int i = 1; i < argc; ++i)
      if (std::string_view(argv[i]) == "--help" || std::string_view(argv[i]) == "-h") {
        print_help();
        std::exit(0);
      }
    for (int i = 1; i < argc; ++i) {
      const std::string key = argv[i];
      const Option* option = key.starts_with("--") ? find(key.substr(2)) : nullptr;
      if (option == nullptr) fail("unknown option '" + key + "'");
      if (option->value == "off") {
        values_[option->name] = "on";
        continue;
      }
      if (i + 1 >= argc) fail("option " + key + " needs a value");
      values_[option->name] = argv[++i];
    }
    for (const Option& option : options_)
      if (option.accepts.test && !option.accepts.test(values_.at(option.name)))
        refuse(option.name, option.accepts.range);
    prepare_out_dir();
  }

  [[nodiscard]] std::string text(const std::string& key) const { return values_.at(key); }
  /// A switch given on the command line.
  [[nodiscard]] bool on(const std::string& key) const { return values_.at(key) == "on"; }
  [[nodiscard]] double number(const std::string& key) const {
    const auto value = parse_number(values_.at(key));
    if (!value) fail("option --" + key + " expects a number, got '" + values_.at(key) + "'");
    return *value;
  }
  /// The value of a flag declared with `integer_in`.
  [[nodiscard]] long long integer(const std::string& key) const { return std::llround(number(key)); }
  /// The folder of `--out`, created and found writable at construction.
  [[nodiscard]] std::filesystem::path out_dir() const { return values_.at("out"); }

  /// Refuses the value of `key`, as a bad value of a single flag is, unless
  /// `valid`: for a range that depends on other flags ("in [100, 300)").
  void require(bool valid, const std::string& key, const std::string& range) const {
    if (!valid) refuse(key, range);
  }

 private:
  [[nodiscard]] const Option* find(const std::string& name) const {
    const auto it = std::find_if(options_.begin(), options_.end(), [&](const Option& o) { return o.name == name; });
    return it == options_.end() ? nullptr : &*it;
  }

  [[noreturn]] void refuse(const std::string& key, const std::string& range) const {
    const std::string& unit = find(key)->unit;
    fail("--" + key + (unit.empty() ? "" : " (" + unit + ")") + " must be " + range + ", got " + values_.at(key));
  }

  [[noreturn]] void fail(const std::string& what) const {
    std::cerr << program_ << ": " << what << " (try --help)\n";
    std::exit(2);
  }

  // Created, and a file written and removed in it, so that a run cannot end
  // in an unwritable folder after its work.
  void prepare_out_dir() const {
    const std::string& dir = values_.at("out");
    const auto refuse_dir = [&](const std::string& why) {
      fail("--out must be a writable directory, got " + dir + ": " + why);
    };
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) refuse_dir("cannot create it: " + error.message());
    if (!std::filesystem::is_directory(dir, error)) refuse_dir("not a directory");
    const std::filesystem::path probe = std::filesystem::path(dir) / ("." + program_ + ".write-test");
    {
      std::ofstream file(probe);
      file << "write test\n";
      file.close();
      if (!file) refuse_dir("cannot write a file in it");
    }
    std::filesystem::remove(probe, error);
  }

  void print_help() const {
    std::size_t width = 0;
    const auto head = [](const Option& o) { return "--" + o.name + (o.value == "off" ? "" : " " + o.value); };
    for (const Option& option : options_) width = std::max(width, head(option).size());
    std::cout << "usage: " << program_ << " [--flag value | --switch]...\n"
              << "Every value is checked before the run: a bad one is refused with exit code 2.\n";
    for (const Option& option : options_) {
      std::string line = "  " + head(option);
      line.resize(width + 4, ' ');
      line += option.value == "off" ? "switch: " + option.description : option.description;
      if (!option.unit.empty()) line += " (" + option.unit + ")";
      if (!option.accepts.range.empty()) line += ": " + option.accepts.range;
      std::cout << line << '\n';
    }
    std::string help = "  --help";
    help.resize(width + 4, ' ');
    std::cout << help << "this text\n";
  }

  std::string program_;
  std::vector<Option> options_;
  std::map<std::string, std::string> values_;
};

/// The end of a run that threw, for `main`'s function-try-block
/// (`int main(...) try { ... } catch (...) { return failure("name"); }`): the
/// message on one line of stderr, and exit code 2 when the library refused a
/// configuration (a bad argument the flags' checks let through), 1 otherwise.
[[nodiscard]] inline int failure(std::string_view program) {
  std::string message = "unknown exception";
  int code = 1;
  try {
    throw;
  } catch (const ConfigurationError& e) {
    message = std::string(e.what()) + " (try --help)";
    code = 2;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
  }
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::cerr << program << ": " << message << '\n';
  return code;
}

/// `--seed`: an integer seed of the example's random draws.
[[nodiscard]] inline Option seed_option(std::string value, std::string description) {
  return {"seed", std::move(value), std::move(description), "", integer_in(0, 1e15)};
}

/// `--noise`: the standard deviation of the output noise.
[[nodiscard]] inline Option noise_option(std::string value,
                                         std::string description = "output noise, standard deviation") {
  return {"noise", std::move(value), std::move(description), "", real_in(0, 1e3)};
}

/// The options plus the lost-measurement flags: `--drop P` (each output sample
/// lost with probability P) and `--outage T0,T1` (no output in [T0, T1], times in `time_unit`).
inline std::vector<Option> with_output_loss(std::vector<Option> options, const std::string& time_unit) {
  options.push_back({"drop", "0", "probability that an output sample is lost", "", real_in(0, 1, "[)")});
  options.push_back({"outage", "none", "no output arrives for t in [T0, T1]", time_unit, interval_or_none()});
  return options;
}

/// The loss model of `--drop` and `--outage`, with its own seed so that the
/// plant's noise does not change when samples are dropped; the outage must
/// begin inside the run, before `end`.
inline OutputLossOptions output_loss_options(const Arguments& args, std::uint64_t seed, double end,
                                             Index channel = -1) {
  OutputLossOptions options{.drop = args.number("drop"), .channel = channel, .seed = seed};
  if (const auto outage = parse_interval(args.text("outage"))) {
    args.require(outage->first < end, "outage",
                 "none or T0,T1 with 0 <= T0 <= T1 and T0 < " + format_number(end) + " (inside the run)");
    options.outage_begin = outage->first;
    options.outage_end = outage->second;
  }
  return options;
}

/// Gnuplot commands that draw, on every later plot, a vertical dotted line at
/// time `t` (in the units of the x axis) with `label` at its top: a fault, the
/// ends of an outage, the start of a monitor.
inline std::string time_marker(double t, std::string_view label, std::string_view color = "#c00000") {
  std::ostringstream gp;
  gp.precision(10);
  gp << "set arrow from " << t << ", graph 0 to " << t << ", graph 1 nohead front dt 3 lw 1.5 lc rgb '" << color
     << "'\nset label '" << label << "' at " << t << ", graph 1 offset 0.4, -0.8 front textcolor rgb '" << color
     << "'\n";
  return gp.str();
}

/// Gnuplot function `floored(v, lo)`: v, or lo where v is smaller, NaN staying
/// NaN. A log axis drops a zero (a statistic at rest, an error that is exactly
/// 0); plotted through it, such a sample shows at lo, which the panel names
/// (in its title, axis label or legend).
inline constexpr const char* log_floor_function = "floored(v, lo) = v != v ? NaN : (v > lo ? v : lo)\n";

/// Gnuplot commands that shade, on every later plot, the stretches of `table`
/// whose samples lacked an output channel (column `y_available` below its
/// largest value), from the first such sample to the next complete one, and a
/// label naming the losses of `options` ("" when nothing was lost); an outage's
/// beginning and end are marked by dotted lines.
inline std::string gap_shading(const SeriesTable& table, const OutputLossOptions& options) {
  const std::vector<double> t = table.column("t");
  const std::vector<double> available = table.column("y_available");
  if (available.empty()) return "";
  const double complete = *std::max_element(available.begin(), available.end());
  std::ostringstream gp;
  int tag = 1;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (available[k] >= complete) continue;
    const std::size_t first = k;
    while (k + 1 < t.size() && available[k + 1] < complete) ++k;
    const double end = k + 1 < t.size() ? t[k + 1] : t[k];
    gp << "set object " << tag++ << " rect from " << t[first] << ", graph 0 to " << end
       << ", graph 1 behind fillcolor rgb '#e0e0e0' fillstyle solid noborder\n";
  }
  if (tag > 1) {
    gp << "set label 1 'outputs lost (shaded): " << options.drop * 100 << " % at random";
    if (options.outage_begin <= options.outage_end)
      gp << ", outage [" << options.outage_begin << ", " << options.outage_end << "]";
    gp << "' at screen 0.01, screen 0.01\n";
  }
  if (options.outage_begin <= options.outage_end)
    gp << time_marker(options.outage_begin, "outage", "#404040") << time_marker(options.outage_end, "", "#404040");
  return gp.str();
}

/// The line `name = value` with full precision.
[[nodiscard]] inline std::string value_line(std::string_view name, double value) {
  std::ostringstream os;
  os.precision(10);
  os << name << " = " << value << '\n';
  return os.str();
}

/// Prints `name = value` with full precision (vectors as space-separated lists).
inline void print_value(std::string_view name, double value) { std::cout << value_line(name, value); }

template <class Derived>
void print_value(std::string_view name, const Eigen::DenseBase<Derived>& m) {
  std::ostringstream os;
  os.precision(10);
  os << name << " = [";
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) os << (j ? " " : "") << m(i, j);
    if (i + 1 < m.rows()) os << "; ";
  }
  os << "]\n";
  std::cout << os.str();
}

inline void print_text(std::string_view name, std::string_view value) { std::cout << name << " = " << value << '\n'; }

[[nodiscard]] inline bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

/// One CSV of a figure drawn from several runs: the table, the file name
/// (without `.csv`) and the gnuplot variable that holds its path.
struct FigureData {
  const SeriesTable& table;
  std::string file;
  std::string variable;
};

/// Writes DIR/<file>.csv for every run, then renders DIR/<name>.png (`size`:
/// "width,height" in pixels) from a gnuplot script that reads each CSV through
/// its variable, when gnuplot is present.
inline void write_outputs(const std::vector<FigureData>& runs, const std::filesystem::path& dir,
                          const std::string& name, const std::string& gnuplot_body,
                          const std::string& size = "1200,900") {
  std::ostringstream variables;
  for (const FigureData& run : runs) {
    const std::filesystem::path csv = dir / (run.file + ".csv");
    run.table.write_csv(csv.string());
    print_text("csv", csv.string());
    variables << run.variable << " = '" << csv.string() << "'\n";
  }
  if (!gnuplot_available()) {
    print_text("png", "skipped (gnuplot not found)");
    return;
  }
  const std::filesystem::path png = dir / (name + ".png");
  const std::filesystem::path script = dir / (name + ".gp");
  {
    std::ofstream gp(script);
    gp << variables.str() << "png = '" << png.string() << "'\n"
       << "set datafile separator ','\n"
       << "set key autotitle columnhead\n"
       << "set terminal pngcairo size " << size << " font ',10'\n"
       << "set output png\n"
       << gnuplot_body << '\n'
       << "unset output\n";
  }
  const std::string command = "gnuplot '" + script.string() + "'";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("gnuplot failed on " + script.string());
  print_text("png", png.string());
}

/// Writes DIR/<name>.csv, then renders DIR/<name>.png from a gnuplot script
/// (the script reads the CSV as `csv` and writes `png`) when gnuplot is present.
inline void write_outputs(const SeriesTable& table, const std::filesystem::path& dir, const std::string& name,
                          const std::string& gnuplot_body, const std::string& size = "1200,900") {
  write_outputs({{table, name, "csv"}}, dir, name, gnuplot_body, size);
}

}  // namespace adaptobs::examples
