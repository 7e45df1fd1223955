// ffr-sim --vtk: the ParaView collection of a run (vtk_series.hpp says what is in it).
#include "vtk_series.hpp"

#include "stl_reader.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/json_input.hpp"
#include "ffr/formats/modal_stress.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/stale_temp.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <sstream>

namespace ffr::vtk {

namespace fs = std::filesystem;
using formats::FormatError;
using runtime::Matrix3d;
using runtime::Vector3d;

namespace {

// One body's geometry in its frame, and where its pose is among the recorded outputs.
struct BodyView {
  int body = -1;
  std::size_t frame_output = 0;  // 4 node_position outputs: the frame's origin, origin + e_x, e_y, e_z
  std::size_t q_output = 0;      // modal coordinates (flexible bodies)
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> vertices;
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor> triangles;
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> modes;  // [nq][Nv,3]
  std::optional<formats::ModalStress> stress;
  // per vertex: the rows of /stress at its position (a shell node has three layers, a node of a
  // solid and a shell four); the vertex shows the largest von Mises stress among them
  std::vector<std::vector<Eigen::Index>> stress_rows;
};

// The uniform box with the body's mass and second moments about the centre of mass: sides
// a_i = sqrt(12 lambda_i / m) along the principal axes, lambda_i the eigenvalues of
// int (c - c_G)(c - c_G)^T dm = J0 - m c_G c_G^T. A side of zero (a point mass, a thin rod) is
// drawn as a hundredth of the largest one, or 1 mm for a point.
void inertia_box(const runtime::Body& b, BodyView& v) {
  const Vector3d cg = b.rdm / b.mass;
  const Matrix3d C = b.J0 - b.mass * cg * cg.transpose();
  const Eigen::SelfAdjointEigenSolver<Matrix3d> es(0.5 * (C + C.transpose()));
  Vector3d a;
  for (int i = 0; i < 3; ++i) a[i] = std::sqrt(12 * std::max(0.0, es.eigenvalues()[i]) / b.mass);
  const double amax = a.maxCoeff();
  for (int i = 0; i < 3; ++i) a[i] = std::max(a[i], amax > 0 ? 0.01 * amax : 1e-3);
  v.vertices.resize(8, 3);
  for (int c = 0; c < 8; ++c) {
    const Vector3d s((c & 1) ? 0.5 : -0.5, (c & 2) ? 0.5 : -0.5, (c & 4) ? 0.5 : -0.5);
    v.vertices.row(c) = (cg + es.eigenvectors() * s.cwiseProduct(a)).transpose();
  }
  static const int kTriangles[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  v.triangles.resize(12, 3);
  for (int t = 0; t < 12; ++t)
    for (int j = 0; j < 3; ++j) v.triangles(t, j) = kTriangles[t][j];
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);  // round-trip exact: ParaView differences frames
  return buf;
}

// A rigid body's surface from its "visual" STL file (global, initial configuration) in its frame.
void given_surface(const runtime::Body& b, const fs::path& stl, BodyView& v) {
  SurfaceMesh m = read_stl(stl);
  v.vertices.resize(m.vertices.rows(), 3);
  for (Eigen::Index p = 0; p < m.vertices.rows(); ++p)
    v.vertices.row(p) = (b.A0.transpose() * (m.vertices.row(p).transpose() - b.r0)).transpose();
  v.triangles = std::move(m.triangles);
}

// The "visual" files of the model file's rigid bodies, by body name, resolved against its folder.
// The runtime's parser has checked the key (a string naming an .stl file on a rigid body); the
// runtime itself never reads it, so the model keeps no trace of it.
std::map<std::string, fs::path> visual_files(const fs::path& model_file) {
  std::map<std::string, fs::path> out;
  const auto doc = formats::JsonDocument::load(model_file);
  for (const auto& b : doc.root().at("bodies").items())
    if (b.has("visual")) out[b.at("name").string()] = model_file.parent_path() / b.at("visual").string();
  return out;
}

// The temporary name of a frames folder or collection of this process (stale_temp.hpp: a
// killed run's ones are found and removed by the next run).
fs::path temporary(const fs::path& target) {
  std::random_device rd;
  return formats::h5::detail::temporary_name(target, (static_cast<unsigned long long>(rd()) << 32) ^ rd());
}

bool is_frame_name(const std::string& s) { return std::regex_match(s, std::regex("frame_[0-9]{6,}\\.vtu")); }

}  // namespace

struct Series::Impl {
  fs::path pvd, frames, temp;
  std::size_t user_outputs = 0;
  std::vector<BodyView> views;
  bool any_stress = false;
  std::vector<double> times;
  bool committed = false;
};

Series::Series(const fs::path& pvd, const fs::path& model_file, runtime::Model& model) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.pvd = pvd;
  if (pvd.extension() != ".pvd") throw std::invalid_argument("--vtk " + pvd.string() + ": the collection's name must end in .pvd");
  // (That its folder exists, ffr-sim's check of every output has made sure: cli/output_files.hpp.)
  const fs::path dir = pvd.parent_path().empty() ? fs::path(".") : pvd.parent_path();
  std::error_code ec;
  s.frames = dir / (pvd.stem().string() + "_frames");
  // The folder is replaced at the end: refused now if it holds anything but frames of an earlier run.
  if (fs::exists(s.frames, ec)) {
    if (!fs::is_directory(s.frames, ec))
      throw std::invalid_argument("--vtk " + pvd.string() + ": " + s.frames.string() + " exists and is not a folder of frames");
    for (const auto& e : fs::directory_iterator(s.frames))
      if (!is_frame_name(e.path().filename().string()))
        throw std::invalid_argument("--vtk " + pvd.string() + ": " + s.frames.string() + " holds " +
                                    e.path().filename().string() + ", which is not a frame; it would be replaced");
  }
  // Frames folders and collections of earlier runs killed before their end.
  formats::h5::detail::remove_stale_temporary_folders(s.frames);
  formats::h5::detail::remove_stale_temporaries(s.pvd);
  s.temp = temporary(s.frames);
  const auto visuals = visual_files(model_file);

  s.user_outputs = model.outputs.size();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const runtime::Body& b = model.bodies[i];
    BodyView v;
    v.body = static_cast<int>(i);
    if (b.flexible) {
      const fs::path sid_path = model_file.parent_path() / b.source;
      formats::Sid sid = formats::read_sid(sid_path);
      if (sid.visual.empty())
        throw FormatError(sid_path.string(), "/visual",
                          "body '" + b.name + "': the SID has no surface, which --vtk draws; reduce the part with "
                          "\"visual\": true (the default)");
      v.vertices = std::move(sid.visual.vertices);
      v.triangles = std::move(sid.visual.triangles);
      v.modes = std::move(sid.visual.modes);
      v.stress = formats::read_modal_stress(sid_path);
      if (v.stress) {
        std::map<std::array<double, 3>, std::vector<Eigen::Index>> at;
        for (Eigen::Index r = 0; r < v.stress->size(); ++r)
          at[{v.stress->position(r, 0), v.stress->position(r, 1), v.stress->position(r, 2)}].push_back(r);
        v.stress_rows.assign(static_cast<std::size_t>(v.vertices.rows()), {});
        for (Eigen::Index p = 0; p < v.vertices.rows(); ++p) {
          const auto it = at.find({v.vertices(p, 0), v.vertices(p, 1), v.vertices(p, 2)});
          if (it != at.end()) v.stress_rows[static_cast<std::size_t>(p)] = it->second;
        }
        s.any_stress = true;
      }
      runtime::Output q;
      q.name = "vtk:" + b.name + ":q";
      q.type = runtime::OutputType::ModalCoordinates;
      q.body = v.body;
      q.size = b.nq;
      v.q_output = model.outputs.size();
      model.outputs.push_back(q);
    } else if (const auto it = visuals.find(b.name); it != visuals.end()) {
      given_surface(b, it->second, v);
    } else {
      inertia_box(b, v);
    }
    v.frame_output = model.outputs.size();
    for (int p = 0; p < 4; ++p) {
      runtime::Output o;
      o.name = "vtk:" + b.name + ":frame" + std::to_string(p);
      o.type = runtime::OutputType::NodePosition;
      o.body = v.body;
      o.point = p == 0 ? Vector3d::Zero() : Vector3d(Vector3d::Unit(p - 1));
      o.size = 3;
      model.outputs.push_back(o);
    }
    s.views.push_back(std::move(v));
  }
}

Series::~Series() {
  if (!impl_->committed) {
    std::error_code ec;
    fs::remove_all(impl_->temp, ec);
  }
}

std::size_t Series::user_outputs() const { return impl_->user_outputs; }

void Series::write_frames(const runtime::Model& model, const runtime::Recorder& rec) {
  Impl& s = *impl_;
  std::error_code ec;
  fs::remove_all(s.temp, ec);
  fs::create_directories(s.temp);
  // The connectivity does not change over time: written once as text.
  std::ostringstream conn, offsets, types, body;
  std::int64_t np = 0, nc = 0;
  for (const BodyView& v : s.views) {
    for (Eigen::Index t = 0; t < v.triangles.rows(); ++t) {
      for (int j = 0; j < 3; ++j) conn << np + v.triangles(t, j) << ' ';
      offsets << 3 * (nc + t + 1) << ' ';
      types << "5 ";
      body << v.body << ' ';
    }
    np += v.vertices.rows();
    nc += v.triangles.rows();
  }
  s.times.clear();
  for (std::int64_t r = 0; r < rec.rows(); ++r) {
    s.times.push_back(rec.times()(r));
    std::ostringstream points, disp, mises, known;
    for (const BodyView& v : s.views) {
      const auto& P = rec.values(v.frame_output);
      const Vector3d o = P.row(r).transpose();
      Matrix3d A;
      for (int a = 0; a < 3; ++a) A.col(a) = rec.values(v.frame_output + 1 + static_cast<std::size_t>(a)).row(r).transpose() - o;
      const bool flexible = model.bodies[static_cast<std::size_t>(v.body)].flexible;
      Eigen::VectorXd q;
      if (flexible) q = rec.values(v.q_output).row(r).transpose();
      formats::ModalStress::RowsX6 S;
      if (v.stress) {
        S = formats::ModalStress::RowsX6::Zero(v.stress->size(), 6);
        for (Eigen::Index k = 0; k < q.size(); ++k) S += q(k) * v.stress->modes[static_cast<std::size_t>(k)];
      }
      for (Eigen::Index p = 0; p < v.vertices.rows(); ++p) {
        Vector3d u = Vector3d::Zero();
        for (Eigen::Index k = 0; k < q.size(); ++k) u += q(k) * v.modes[static_cast<std::size_t>(k)].row(p).transpose();
        const Vector3d x = o + A * (v.vertices.row(p).transpose() + u), ug = A * u;
        points << number(x.x()) << ' ' << number(x.y()) << ' ' << number(x.z()) << '\n';
        disp << number(ug.x()) << ' ' << number(ug.y()) << ' ' << number(ug.z()) << '\n';
        const bool has = v.stress && !v.stress_rows[static_cast<std::size_t>(p)].empty();
        double vm = 0;
        if (has)
          for (const Eigen::Index row : v.stress_rows[static_cast<std::size_t>(p)])
            vm = std::max(vm, formats::von_mises(S.row(row).transpose()));
        mises << (has ? number(vm) : std::string("0")) << '\n';
        known << (has ? "1 " : "0 ");
      }
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06lld.vtu", static_cast<long long>(r));
    std::ofstream f(s.temp / name);
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n"
      << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n" << points.str()
      << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n" << conn.str()
      << "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n" << offsets.str()
      << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n" << types.str()
      << "\n</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\"" << (s.any_stress ? " Scalars=\"von_mises\"" : "")
      << ">\n<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n" << disp.str()
      << "</DataArray>\n";
    if (s.any_stress)
      f << "<DataArray type=\"Float64\" Name=\"von_mises\" format=\"ascii\">\n" << mises.str()
        << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"has_stress\" format=\"ascii\">\n" << known.str() << "\n</DataArray>\n";
    f << "</PointData>\n<CellData Scalars=\"body\">\n<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n" << body.str()
      << "\n</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    f.close();
    if (!f) throw std::runtime_error((s.temp / name).string() + ": writing the frame failed");
  }
}

void Series::commit() {
  Impl& s = *impl_;
  std::error_code ec;
  fs::remove_all(s.frames, ec);  // only frames of an earlier run (checked before the run)
  fs::rename(s.temp, s.frames);
  const fs::path tmp = temporary(s.pvd);
  {
    std::ofstream f(tmp);
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n";
    for (std::size_t r = 0; r < s.times.size(); ++r) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06lld.vtu", static_cast<long long>(r));
      char t[32];
      std::snprintf(t, sizeof t, "%.17g", s.times[r]);
      f << "<DataSet timestep=\"" << t << "\" part=\"0\" file=\""
        << (s.frames.filename() / name).string() << "\"/>\n";
    }
    f << "</Collection>\n</VTKFile>\n";
    f.close();
    if (!f) {
      fs::remove(tmp, ec);
      throw std::runtime_error(s.pvd.string() + ": writing the collection failed");
    }
  }
  fs::rename(tmp, s.pvd);
  s.committed = true;
}

}  // namespace ffr::vtk
