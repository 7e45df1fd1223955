#include "node_dof_entries.hpp"

#include "../mesh/bdf_cards.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"

#include <charconv>
#include <cmath>

namespace ffr::preproc::detail {
namespace {

using formats::FormatError;

std::string read(const std::filesystem::path& file) {
  try {
    return formats::read_text_file(file);
  } catch (const std::exception& e) {
    throw FormatError(file.string(), "file", std::string("cannot be read: ") + e.what());
  }
}

std::string trimmed(std::string_view s) { return bdf_trim(s); }

bool to_long(const std::string& s, long long& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// Abaqus writes E exponents; a Fortran D is taken as well.
bool to_double(std::string s, double& v) {
  for (char& c : s)
    if (c == 'D' || c == 'd') c = 'E';
  const char* b = s.data();
  if (!s.empty() && s[0] == '+') ++b;
  const auto r = std::from_chars(b, s.data() + s.size(), v);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

}  // namespace

std::vector<NodeDofEntry> read_abaqus_matrix(const std::filesystem::path& file) {
  const std::string text = read(file);
  std::vector<NodeDofEntry> out;
  std::size_t p = 0;
  int line = 0;
  while (p < text.size()) {
    const std::size_t e = text.find('\n', p);
    const std::string l = trimmed(std::string_view(text).substr(p, e == std::string::npos ? std::string::npos : e - p));
    p = e == std::string::npos ? text.size() : e + 1;
    ++line;
    if (l.empty() || l.rfind("**", 0) == 0) continue;
    const auto at = [&](const std::string& what) { return FormatError(file.string(), "line " + std::to_string(line), what); };
    if (l[0] == '*')
      throw at("keyword line '" + l + "': the file of *MATRIX OUTPUT, FORMAT=MATRIX INPUT holds only '**' comments and " +
               "'row node, row DOF, column node, column DOF, value' lines");
    std::vector<std::string> f;
    std::size_t b = 0;
    for (;;) {
      const std::size_t c = l.find(',', b);
      f.push_back(trimmed(std::string_view(l).substr(b, c == std::string::npos ? std::string::npos : c - b)));
      if (c == std::string::npos) break;
      b = c + 1;
    }
    NodeDofEntry n{};
    n.line = line;
    if (f.size() != 5 || !to_long(f[0], n.row_node) || !to_long(f[1], n.row_dof) || !to_long(f[2], n.col_node) ||
        !to_long(f[3], n.col_dof) || !to_double(f[4], n.value))
      throw at("'row node, row DOF, column node, column DOF, value' (four integers and a finite number, commas "
               "between) expected, got '" + l + "' (Abaqus *MATRIX OUTPUT, FORMAT=MATRIX INPUT)");
    out.push_back(n);
  }
  if (out.empty()) throw FormatError(file.string(), "file", "no matrix entries (Abaqus *MATRIX OUTPUT, FORMAT=MATRIX INPUT)");
  return out;
}

std::vector<NodeDofEntry> read_dmig_matrix(const std::filesystem::path& file, const std::string& name, bool& square) {
  const std::string fname = file.string();  // Fields keeps a reference to it
  const std::vector<Card> cards = read_cards(fname, read(file));
  const std::string want = bdf_upper(name);
  std::vector<NodeDofEntry> out;
  bool header = false;
  for (const Card& c : cards) {
    const Fields f(fname, c);
    if (c.name != "DMIG")
      f.fail("only DMIG cards are expected in a matrix file (the deck is the \"geometry\")");
    if (f.raw(2) != want) continue;
    if (f.raw(3) == "0") {  // the header: NAME, 0, IFO, TIN, TOUT, POLAR, , NCOL
      if (header) f.fail("a second header card of DMIG " + want);
      header = true;
      const long long ifo = f.integer(4, "IFO");
      if (ifo != 6 && ifo != 1) f.fail(Fields::at(4) + " (IFO) is " + std::to_string(ifo) + ": a symmetric (6) or square (1) matrix is expected");
      square = ifo == 1;
      const long long tin = f.integer(5, "TIN");
      if (tin != 1 && tin != 2) f.fail(Fields::at(5) + " (TIN) is " + std::to_string(tin) + ": real entries (1 or 2) are expected, not complex");
      f.require_zero(7, "POLAR");
      continue;
    }
    if (!header) f.fail("a column of DMIG " + want + " before its header card (field 3 = 0)");
    const long long gj = static_cast<long long>(f.id(3, "GJ")), cj = f.integer(4, "CJ");
    f.require_blank(5, 5, "field 5 of a DMIG column is blank");
    std::size_t k = 6;
    int terms = 0;
    for (; k + 2 < f.size() + 1; k += 4) {
      if (f.blank(k) && f.blank(k + 1) && f.blank(k + 2) && f.blank(k + 3)) continue;  // padding of the last line
      NodeDofEntry n{};
      n.col_node = gj;
      n.col_dof = cj;
      n.row_node = static_cast<long long>(f.id(k, "Gi"));
      n.row_dof = f.integer(k + 1, "Ci");
      n.value = f.real(k + 2, "Ai");
      if (!f.blank(k + 3)) f.fail(Fields::at(k + 3) + " (Bi, the imaginary part) must be blank: real matrices only");
      n.line = f.line();
      out.push_back(n);
      ++terms;
    }
    if (terms == 0) f.fail("a DMIG column without entries (Gi, Ci, Ai from field 6 on)");
  }
  if (!header) throw FormatError(file.string(), "file", "no DMIG header card of matrix " + want + " (\"DMIG, " + want + ", 0, 6, 2, 0\")");
  if (out.empty()) throw FormatError(file.string(), "file", "DMIG " + want + " has a header but no columns");
  return out;
}

}  // namespace ffr::preproc::detail
