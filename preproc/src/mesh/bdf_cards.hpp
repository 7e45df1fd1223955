#pragma once
// Nastran bulk-data cards as the Quick Reference Guide lays them out: small-field, large-field
// and free-field lines with continuations, and their fields read with the card's name and line
// in every message. Shared by the bulk-data mesh reader (bdf_reader.cpp) and the DMIG matrix
// reader (matrix_input/dmig_reader.cpp).
#include "ffr/formats/h5.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ffr::preproc::detail {

std::string bdf_upper(std::string_view s);
std::string bdf_trim(std::string_view s);

// A card: its name (without the large-field '*') and its data fields, field 2 of the first
// line at index 0, 8 fields per small-field line and per two large-field lines, as the
// Nastran Quick Reference Guide numbers them.
struct Card {
  std::string name;
  std::vector<std::string> f;
  int line = 0;
};

/// The bulk data's cards (all of the file when it has no BEGIN BULK), up to ENDDATA. Throws
/// formats::FormatError naming the file and the line.
std::vector<Card> read_cards(const std::string& file, const std::string& text);

// The fields of one card, read with the card's name, line and id in every message.
class Fields {
 public:
  Fields(const std::string& file, const Card& c) : file_(file), c_(c) {}

  [[noreturn]] void fail(const std::string& what) const {
    std::string id = c_.f.empty() ? std::string() : " " + c_.f[0];
    throw formats::FormatError(file_, "line " + std::to_string(c_.line) + " (" + c_.name + id + ")", what);
  }
  // Field k of the card as the Quick Reference numbers it (2 = the first data field).
  const std::string& raw(std::size_t k) const {
    static const std::string blank;
    return k - 2 < c_.f.size() ? c_.f[k - 2] : blank;
  }
  bool blank(std::size_t k) const { return raw(k).empty(); }
  // Field k as the Quick Reference Guide shows it: field 2..9 of the card's first line, or of
  // its n-th continuation line (8 data fields a line).
  static std::string at(std::size_t k) {
    const std::size_t line = (k - 2) / 8, field = (k - 2) % 8 + 2;
    return line == 0 ? "field " + std::to_string(field)
                     : "continuation " + std::to_string(line) + ", field " + std::to_string(field);
  }

  long long integer(std::size_t k, const char* what) const {
    const std::string& s = raw(k);
    long long v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
      fail(at(k) + " (" + what + "): expected an integer, found '" + s + "'");
    return v;
  }
  std::size_t id(std::size_t k, const char* what) const {
    const long long v = integer(k, what);
    if (v < 1) fail(at(k) + " (" + what + "): expected a positive id, found " + raw(k));
    return static_cast<std::size_t>(v);
  }
  long long integer_or(std::size_t k, const char* what, long long dflt) const { return blank(k) ? dflt : integer(k, what); }

  // Nastran reals: 1.5E-3, 1.5D-3, 1.5-3 (an exponent without E), 7.+4, .5; integers too.
  double real(std::size_t k, const char* what) const {
    std::string s = raw(k);
    for (char& ch : s)
      if (ch == 'D') ch = 'E';
    if (s.find('E') == std::string::npos)
      for (std::size_t i = 1; i < s.size(); ++i)
        if ((s[i] == '+' || s[i] == '-') && s[i - 1] != 'E') {
          s = s.substr(0, i) + 'E' + s.substr(i);
          break;
        }
    const char* b = s.data();
    if (!s.empty() && s[0] == '+') ++b;
    double v = 0;
    const auto r = std::from_chars(b, s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
      fail(at(k) + " (" + what + "): expected a number, found '" + raw(k) + "'");
    return v;
  }
  std::optional<double> real_opt(std::size_t k, const char* what) const {
    return blank(k) ? std::nullopt : std::optional<double>(real(k, what));
  }
  double real_or(std::size_t k, const char* what, double dflt) const { return blank(k) ? dflt : real(k, what); }

  // Fields that would change the model: refused unless blank (or zero).
  void require_blank(std::size_t first, std::size_t last, const char* why) const {
    for (std::size_t k = first; k <= last; ++k)
      if (!blank(k)) fail(at(k) + " ('" + raw(k) + "') is not supported: " + why);
  }
  void require_zero(std::size_t k, const char* what) const {
    if (!blank(k) && real(k, what) != 0.0) fail(at(k) + " (" + what + ") is not supported unless 0");
  }
  std::size_t size() const { return c_.f.size() + 1; }  // the last field number
  int line() const { return c_.line; }

 private:
  const std::string& file_;
  const Card& c_;
};

}  // namespace ffr::preproc::detail
