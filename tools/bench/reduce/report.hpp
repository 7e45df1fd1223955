#pragma once
// Output of the benchmarks: one table printed as aligned text on stdout and as Markdown in
// the report file, plus number formatting.

#include <string>
#include <vector>

namespace ffr::bench {

class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  bool empty() const { return rows_.empty(); }
  std::string text() const;      ///< aligned columns, for the terminal
  std::string markdown() const;  ///< GitHub table, numbers right-aligned

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/// Fixed-point with `digits` decimals.
std::string fixed(double v, int digits);
/// Three significant digits, scientific below 1e-3 ("3.1e-07").
std::string sig3(double v);
/// 1234567 -> "1 234 567".
std::string grouped(long long v);
/// Seconds as "12.3" (or "1234" above 1000).
std::string secs(double s);

/// Appends `text` to the file (creating it).
void append_file(const std::string& path, const std::string& text);

}  // namespace ffr::bench
