#include "export.hpp"

#include "ffr/cli/output_files.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/validate.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace ffr::info {
namespace {

using formats::Index;
using formats::Sid;

Sid read_valid(const std::string& file) {
  Sid sid = formats::read_sid(file);
  const auto report = formats::validate(sid);
  if (!report.ok())
    for (const auto& c : report.checks)
      if (c.applicable && !c.pass)
        throw formats::FormatError(file, c.name, "fails validation: nothing exported (" + c.note + ")");
  return sid;
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// `text` to `path` through a temporary file renamed over it: a failed export leaves nothing.
void write_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    f.close();
    if (!f) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error("cannot write " + path.string());
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path.string());
  }
}

using Entry2 = std::function<double(Index, Index)>;
using Entry3 = std::function<double(Index, Index, Index)>;

// One Taylor member of the SID_FEM file: X(q) = M0 + sum_k q_k M1(:, :, k), every entry
// written (structure 3, full matrix).
void taylor(std::ostream& o, const char* name, Index nrow, Index ncol, Index nq, const Entry2& m0, const Entry3* m1) {
  o << name << "\n";
  o << "    order        = " << (m1 ? 1 : 0) << "\n";
  o << "    nrow         = " << nrow << "\n";
  o << "    ncol         = " << ncol << "\n";
  o << "    nq           = " << (m1 ? nq : 0) << "\n";
  o << "    nqn          = 0\n";
  o << "    structure    = 3\n";
  for (Index i = 0; i < nrow; ++i)
    for (Index j = 0; j < ncol; ++j) o << "    m0( " << i + 1 << ", " << j + 1 << ") = " << num(m0(i, j)) << "\n";
  if (m1)
    for (Index i = 0; i < nrow; ++i)
      for (Index j = 0; j < ncol; ++j)
        for (Index k = 0; k < nq; ++k)
          o << "    m1( " << i + 1 << ", " << j + 1 << ", " << k + 1 << ") = " << num((*m1)(i, j, k)) << "\n";
  o << "end " << name << "\n";
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

std::string fbi_text(const Sid& s) {
  const Index nq = s.nq();
  const bool stiff = s.stiffening.has_value();
  std::ostringstream o;
  o << "part\nnew modal\nrefmod\n";
  o << "    mass           = " << num(s.refmod.mass) << "\n";
  o << "    nelastq        = " << nq << "\n";
  for (Index k = 0; k < nq; ++k) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "Eigen Mode %lld : %.9g Hz", static_cast<long long>(k + 1), s.refmod.frequency_hz(k));
    o << "    ielastq(" << k + 1 << ") = " << buf << "\n";
  }
  o << "end refmod\nnew frame\n";
  for (Index p = 0; p < s.num_nodes(); ++p) {
    const auto& n = s.nodes[static_cast<std::size_t>(p)];
    o << "new node = " << p + 1 << "\n";
    o << "rframe = body ref\n";
    const Entry3 origin1 = [&](Index i, Index, Index k) { return n.phi(i, k); };
    taylor(o, "origin", 3, 1, nq, [&](Index i, Index) { return n.origin(i); }, &origin1);
    taylor(o, "phi", 3, nq, nq, [&](Index i, Index j) { return n.phi(i, j); }, nullptr);
    taylor(o, "psi", 3, nq, nq, [&](Index i, Index j) { return n.psi(i, j); }, nullptr);
    // A(q) = (I + skew(Psi q)) AP0 to first order: M1(:, :, k) = skew(psi_k) AP0.
    std::vector<Eigen::Matrix3d> ap1(static_cast<std::size_t>(nq));
    for (Index k = 0; k < nq; ++k) ap1[static_cast<std::size_t>(k)] = skew(n.psi.col(k)) * n.AP0;
    const Entry3 ap = [&](Index i, Index j, Index k) { return ap1[static_cast<std::size_t>(k)](i, j); };
    taylor(o, "AP", 3, 3, nq, [&](Index i, Index j) { return n.AP0(i, j); }, &ap);
    o << "end node\n";
  }
  o << "end frame\n";
  const auto K = [](Index k) { return static_cast<std::size_t>(k); };
  const Entry3 md1 = [&](Index i, Index, Index k) { return s.mdCM.M1(k, i); };
  taylor(o, "mdCM", 3, 1, nq, [&](Index i, Index) { return s.mdCM.M0(i); }, &md1);
  const Entry3 j1 = [&](Index i, Index j, Index k) { return s.J.M1[K(k)](i, j); };
  taylor(o, "J", 3, 3, nq, [&](Index i, Index j) { return s.J.M0(i, j); }, &j1);
  // The SID's first-order members include the geometric stiffening (SPEC.md section 10).
  const Entry3 ct1 = [&](Index i, Index c, Index k) { return s.stiffening->K0t[K(k)](i, c); };
  taylor(o, "Ct", nq, 3, nq, [&](Index i, Index c) { return s.Ct.M0(i, c); }, stiff ? &ct1 : nullptr);
  const Entry3 cr1 = [&](Index i, Index c, Index k) {
    return s.Cr.M1[K(k)](i, c) + (stiff ? s.stiffening->K0r[K(k)](i, c) : 0.0);
  };
  taylor(o, "Cr", nq, 3, nq, [&](Index i, Index c) { return s.Cr.M0(i, c); }, &cr1);
  taylor(o, "Me", nq, nq, nq, [&](Index i, Index j) { return s.Me(i, j); }, nullptr);
  taylor(o, "Gr", 3, 3 * nq, nq, [&](Index i, Index j) { return s.Gr[K(j / 3)](i, j % 3); }, nullptr);
  taylor(o, "Ge", nq, 3 * nq, nq, [&](Index i, Index j) { return s.Ge[K(j / 3)](i, j % 3); }, nullptr);
  const Entry3 oe1 = [&](Index i, Index j, Index k) {
    return s.Oe.M1[K(k)](i, j) + (stiff ? s.stiffening->K0om[K(k)](i, j) : 0.0);
  };
  taylor(o, "Oe", nq, 6, nq, [&](Index i, Index j) { return s.Oe.M0(i, j); }, &oe1);
  const Entry3 ks1 = [&](Index i, Index, Index k) { return s.ksigma.M1(k, i); };
  taylor(o, "ksigma", nq, 1, nq, [&](Index i, Index) { return s.ksigma.M0(i); }, &ks1);
  const Entry3 ke1 = [&](Index i, Index j, Index k) { return s.KeM1[K(k)](i, j); };
  taylor(o, "Ke", nq, nq, nq, [&](Index i, Index j) { return s.Ke(i, j); }, s.KeM1.empty() ? nullptr : &ke1);
  taylor(o, "De", nq, nq, nq, [&](Index i, Index j) { return s.De(i, j); }, nullptr);
  o << "end modal\nend part\n";
  return o.str();
}

// A dense matrix in the Matrix Market array format (column by column).
std::string mtx_text(const Eigen::MatrixXd& m, const std::string& comment) {
  std::ostringstream o;
  o << "%%MatrixMarket matrix array real general\n% " << comment << "\n" << m.rows() << " " << m.cols() << "\n";
  for (Index j = 0; j < m.cols(); ++j)
    for (Index i = 0; i < m.rows(); ++i) o << num(m(i, j)) << "\n";
  return o.str();
}

}  // namespace

int run_export_fbi(const std::string& sid_file, const std::string& out) {
  cli::check_outputs({{"-o", out}}, {{"the SID file", sid_file}});
  const Sid sid = read_valid(sid_file);
  write_atomically(out, fbi_text(sid));
  return 0;
}

int run_export_mtx(const std::string& sid_file, const std::string& dir) {
  const Sid sid = read_valid(sid_file);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw cli::UsageError("-o " + dir + ": cannot create the folder" + (ec ? " (" + ec.message() + ")" : std::string()));
  const std::string units = " (units: length " + sid.units_length + ", mass " + sid.units_mass + ", time " + sid.units_time + ")";
  const std::filesystem::path d(dir);
  write_atomically(d / "Me.mtx", mtx_text(sid.Me, "modal mass matrix Me of " + sid_file + units));
  write_atomically(d / "Ke.mtx", mtx_text(sid.Ke, "modal stiffness matrix Ke of " + sid_file + units));
  write_atomically(d / "De.mtx", mtx_text(sid.De, "modal damping matrix De of " + sid_file + units));
  for (std::size_t k = 0; k < sid.KeM1.size(); ++k)
    write_atomically(d / ("KeM1_" + std::to_string(k + 1) + ".mtx"),
                     mtx_text(sid.KeM1[k], "Ke.M1 of mode " + std::to_string(k + 1) + " of " + sid_file + units));
  return 0;
}

}  // namespace ffr::info
