#pragma once
// Command line, stdout and figure helpers shared by every example binary.
//
// Every example takes `--out DIR` (default: current directory), writes
// DIR/<name>.csv, then DIR/<name>.png when gnuplot is on the PATH, and prints
// its designed gains and final estimates as `name = value` lines.

#include <adaptobs/simulation/output_loss.hpp>
#include <adaptobs/simulation/series_table.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace adaptobs::examples {

/// `--key value` options with defaults, and switches: an option whose default
/// is "off" is turned on by `--key` alone. `--help` prints them.
class Arguments {
 public:
  Arguments(int argc, char** argv, std::string_view program, std::map<std::string, std::string> defaults)
      : program_(program), values_(std::move(defaults)) {
    values_.try_emplace("out", ".");
    for (const auto& [k, v] : values_)
      if (v == "off") switches_.insert(k);
    for (int i = 1; i < argc; ++i) {
      const std::string key = argv[i];
      if (key == "--help" || key == "-h") {
        std::cout << "usage: " << program_;
        for (const auto& [k, v] : values_)
          std::cout << " [--" << k << (switches_.contains(k) ? "" : " " + (v.empty() ? std::string("VALUE") : v))
                    << "]";
        std::cout << '\n';
        std::exit(0);
      }
      const std::string name = key.size() > 2 ? key.substr(2) : "";
      if (key.rfind("--", 0) == 0 && switches_.contains(name)) {
        values_[name] = "on";
        continue;
      }
      if (key.rfind("--", 0) != 0 || i + 1 >= argc || !values_.contains(name))
        fail("unknown or incomplete option '" + key + "'");
      values_[name] = argv[++i];
    }
  }

  [[nodiscard]] std::string text(const std::string& key) const { return values_.at(key); }
  /// A switch given on the command line.
  [[nodiscard]] bool on(const std::string& key) const { return values_.at(key) == "on"; }
  [[nodiscard]] double number(const std::string& key) const {
    try {
      return std::stod(values_.at(key));
    } catch (const std::exception&) {
      fail("option --" + key + " expects a number, got '" + values_.at(key) + "'");
    }
  }
  [[nodiscard]] std::filesystem::path out_dir() const {
    std::filesystem::path dir(values_.at("out"));
    std::filesystem::create_directories(dir);
    return dir;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    std::cerr << program_ << ": " << what << " (try --help)\n";
    std::exit(2);
  }
  std::string program_;
  std::map<std::string, std::string> values_;
  std::set<std::string> switches_;
};

/// The defaults plus the lost-measurement flags: `--drop P` (each output sample
/// lost with probability P) and `--outage T0,T1` (no output in [T0, T1]).
inline std::map<std::string, std::string> with_output_loss(std::map<std::string, std::string> defaults) {
  defaults.try_emplace("drop", "0");
  defaults.try_emplace("outage", "none");
  return defaults;
}

/// The loss model of `--drop` and `--outage`, with its own seed so that the
/// plant's noise does not change when samples are dropped.
inline OutputLossOptions output_loss_options(const Arguments& args, std::uint64_t seed, Index channel = -1) {
  OutputLossOptions options{.drop = args.number("drop"), .channel = channel, .seed = seed};
  const std::string outage = args.text("outage");
  if (outage != "none") {
    const auto comma = outage.find(',');
    try {
      if (comma == std::string::npos) throw std::invalid_argument(outage);
      options.outage_begin = std::stod(outage.substr(0, comma));
      options.outage_end = std::stod(outage.substr(comma + 1));
    } catch (const std::exception&) {
      std::cerr << "--outage expects T0,T1, got '" << outage << "'\n";
      std::exit(2);
    }
  }
  return options;
}

/// Gnuplot commands that shade, on every later plot, the stretches of `table`
/// whose samples lacked an output channel (column `y_available` below its
/// largest value), from the first such sample to the next complete one, and a
/// label naming the losses of `options` ("" when nothing was lost).
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
  return gp.str();
}

/// Prints `name = value` with full precision (vectors as space-separated lists).
inline void print_value(std::string_view name, double value) {
  std::ostringstream os;
  os.precision(10);
  os << name << " = " << value << '\n';
  std::cout << os.str();
}

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

/// Writes DIR/<file>.csv for every run, then renders DIR/<name>.png from a
/// gnuplot script that reads each CSV through its variable, when gnuplot is present.
inline void write_outputs(const std::vector<FigureData>& runs, const std::filesystem::path& dir,
                          const std::string& name, const std::string& gnuplot_body) {
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
       << "set terminal pngcairo size 1200,900 font ',10'\n"
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
                          const std::string& gnuplot_body) {
  write_outputs({{table, name, "csv"}}, dir, name, gnuplot_body);
}

}  // namespace adaptobs::examples
