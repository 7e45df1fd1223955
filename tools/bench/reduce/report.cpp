#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ffr::bench {

std::string Table::text() const {
  std::vector<std::size_t> w(header_.size(), 0);
  auto widen = [&](const std::vector<std::string>& r) {
    for (std::size_t i = 0; i < r.size() && i < w.size(); ++i) w[i] = std::max(w[i], r[i].size());
  };
  widen(header_);
  for (const auto& r : rows_) widen(r);
  std::ostringstream o;
  auto line = [&](const std::vector<std::string>& r) {
    for (std::size_t i = 0; i < w.size(); ++i) {
      const std::string c = i < r.size() ? r[i] : "";
      o << (i ? "  " : "") << std::string(w[i] - c.size(), ' ') << c;
    }
    o << "\n";
  };
  line(header_);
  for (const auto& r : rows_) line(r);
  return o.str();
}

std::string Table::markdown() const {
  std::ostringstream o;
  o << "|";
  for (const auto& h : header_) o << " " << h << " |";
  o << "\n|";
  for (std::size_t i = 0; i < header_.size(); ++i) o << (i == 0 ? ":---|" : "---:|");
  o << "\n";
  for (const auto& r : rows_) {
    o << "|";
    for (std::size_t i = 0; i < header_.size(); ++i) o << " " << (i < r.size() ? r[i] : "") << " |";
    o << "\n";
  }
  return o.str();
}

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "—";
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

std::string sig3(double v) {
  if (std::isnan(v)) return "—";
  char b[64];
  if (v != 0 && std::abs(v) < 1e-3) std::snprintf(b, sizeof b, "%.1e", v);
  else std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

std::string grouped(long long v) {
  std::string s = std::to_string(v < 0 ? -v : v), o;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i && (s.size() - i) % 3 == 0) o += ' ';
    o += s[i];
  }
  return v < 0 ? "-" + o : o;
}

std::string secs(double s) {
  if (std::isnan(s)) return "—";
  return s >= 1000 ? fixed(s, 0) : s >= 100 ? fixed(s, 1) : s >= 10 ? fixed(s, 2) : fixed(s, 3);
}

void append_file(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  std::ofstream f(path, std::ios::app);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace ffr::bench
