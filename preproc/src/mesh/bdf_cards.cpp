#include "bdf_cards.hpp"

#include <algorithm>
#include <cctype>

namespace ffr::preproc::detail {

using formats::FormatError;

std::string bdf_upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::string bdf_trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// Small-field (8 characters), large-field (16, the name ending in '*', continuation lines
// starting with '*') and free-field (commas) lines; '$' starts a comment; a line whose first
// field is blank or starts with '+' or '*' continues the card before it.
std::vector<Card> read_cards(const std::string& file, const std::string& text) {
  std::vector<Card> cards;
  // Executive and case control before BEGIN BULK select the solution: passed over.
  bool bulk = true;
  {
    std::size_t p = 0;
    while (p < text.size()) {
      const std::size_t e = text.find('\n', p);
      const std::string l = bdf_upper(bdf_trim(std::string_view(text).substr(p, e == std::string::npos ? std::string::npos : e - p)));
      if (l.rfind("BEGIN", 0) == 0 && l.find("BULK") != std::string::npos) {
        bulk = false;
        break;
      }
      p = e == std::string::npos ? text.size() : e + 1;
    }
  }
  std::size_t p = 0;
  int line_no = 0;
  while (p < text.size()) {
    const std::size_t e = text.find('\n', p);
    std::string raw = text.substr(p, e == std::string::npos ? std::string::npos : e - p);
    p = e == std::string::npos ? text.size() : e + 1;
    ++line_no;
    if (const auto c = raw.find('$'); c != std::string::npos) raw.erase(c);
    // Tabs to the next multiple of 8 columns.
    std::string l;
    for (char c : raw) {
      if (c == '\r') continue;
      if (c == '\t') l.append(8 - l.size() % 8, ' ');
      else l += c;
    }
    const std::string t = bdf_upper(bdf_trim(l));
    if (t.empty()) continue;
    if (!bulk) {
      if (t.rfind("BEGIN", 0) == 0 && t.find("BULK") != std::string::npos) bulk = true;
      continue;
    }
    if (t.rfind("ENDDATA", 0) == 0) break;
    const auto at = [&](const std::string& what) { return FormatError(file, "line " + std::to_string(line_no), what); };

    std::string first;
    std::vector<std::string> data;
    if (l.find(',') != std::string::npos) {
      std::vector<std::string> parts;
      std::size_t b = 0;
      for (;;) {
        const std::size_t c = l.find(',', b);
        parts.push_back(bdf_upper(bdf_trim(std::string_view(l).substr(b, c == std::string::npos ? std::string::npos : c - b))));
        if (c == std::string::npos) break;
        b = c + 1;
      }
      first = parts[0];
      const bool large = (!first.empty() && first.back() == '*') || (!first.empty() && first[0] == '*');
      const std::size_t per_line = large ? 4 : 8;
      data.assign(parts.begin() + 1, parts.end());
      // A last field beyond the line's data fields is its continuation marker.
      if (data.size() == per_line + 1) {
        // Never a data field: a number there would be lost.
        if (!data.back().empty() && data.back()[0] != '+' && data.back()[0] != '*')
          throw at("field 10 of a free-field line is its continuation marker (blank, '+...' or '*...'), found '" +
                   data.back() + "': " + std::to_string(per_line) + " data fields a line");
        data.pop_back();
      }
      if (data.size() > per_line)
        throw at("a free-field line holds at most " + std::to_string(per_line) +
                 " data fields and a continuation marker; found " + std::to_string(data.size()));
      data.resize(per_line);
    } else {
      first = bdf_upper(bdf_trim(l.substr(0, std::min<std::size_t>(8, l.size()))));
      const bool large = (!first.empty() && first.back() == '*') || (!first.empty() && first[0] == '*');
      const std::size_t width = large ? 16 : 8, count = large ? 4 : 8;
      for (std::size_t k = 0; k < count; ++k) {
        const std::size_t b = 8 + k * width;
        data.push_back(b < l.size() ? bdf_upper(bdf_trim(l.substr(b, std::min(width, l.size() - b)))) : std::string());
      }
      if (l.size() > 80 && !bdf_trim(l.substr(80)).empty()) throw at("characters beyond column 80 of a fixed-field line");
    }
    const bool continuation = first.empty() || first[0] == '+' || first[0] == '*';
    if (continuation) {
      if (cards.empty()) throw at("a continuation line without a card before it");
      cards.back().f.insert(cards.back().f.end(), data.begin(), data.end());
    } else {
      Card c;
      c.name = first.back() == '*' ? first.substr(0, first.size() - 1) : first;
      c.f = std::move(data);
      c.line = line_no;
      cards.push_back(std::move(c));
    }
  }
  if (!bulk) throw FormatError(file, "", "BEGIN BULK without bulk data after it");
  return cards;
}


}  // namespace ffr::preproc::detail
