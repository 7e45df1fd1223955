// "bodies": rigid bodies and flexible bodies from SID files, with their initial state.
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/validate.hpp"
#include "ffr/runtime/load.hpp"
#include "parse.hpp"

#include <Eigen/SVD>

#include <cctype>
#include <cstdio>
#include <set>

namespace ffr::runtime::detail {
namespace {

Matrix3d orientation(const std::optional<Field>& f) {
  if (!f) return Matrix3d::Identity();
  // Rows as written; the matrix maps body components to global ones (columns = body axes).
  const Matrix3d A = f->mat3();
  if ((A.transpose() * A - Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 || A.determinant() < 0)
    f->fail("must be a rotation matrix (orthonormal, determinant +1)");
  // Re-orthonormalise what passed the check so the frame constraints hold to round-off.
  Eigen::JacobiSVD<Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

formats::Sid read_sid_for(const Field& f, const std::filesystem::path& base, std::vector<std::string>& notes) {
  const std::filesystem::path p = base / f.string();
  const std::string referred = " (" + f.file() + ": " + f.path() + ")";
  formats::Sid sid;
  try {
    sid = formats::read_sid(p, &notes);  // a version 1 SID is read with a note: no content checksums
  } catch (const formats::FormatError& e) {
    // Keep the SID's own file and dataset, say where the model refers to it.
    throw ModelError(e.file(), e.object(), e.detail() + referred);
  }
  // A readable SID can still be wrong. A failed property (a negative-definite Ke gave motion
  // without a warning) is refused; a failed identity (members that disagree with the
  // integrals, free modes not orthogonal to the rigid motion: bodies made by hand or by other
  // tools) is reported, since the formulation takes the members as given. ffr-info lists every
  // check.
  const formats::ValidationReport report = formats::validate(sid);
  bool noted = false;
  for (const formats::Check& c : report.checks) {
    if (!c.applicable || c.pass) continue;
    char rel[64];
    std::snprintf(rel, sizeof rel, "relative violation %.3g > %.3g", c.rel, c.tol);
    const std::string what = c.name + " (" + rel + (c.note.empty() ? "" : "; " + c.note) + ")";
    if (c.kind == formats::Check::Kind::Property) throw ModelError(p.string(), c.where, "fails the SID validation: " + what + referred);
    if (!noted) {
      noted = true;
      notes.push_back(p.string() + ": " + std::to_string(report.failures()) + " SID validation check(s) fail, first " + what +
                      "; ffr-info lists them" + referred);
    }
  }
  return sid;
}

void initial_motion(const Field& b, Body& body) {
  if (auto f = b.find("velocity")) body.v0 = f->vec3();
  if (auto f = b.find("angular_velocity")) body.w0 = f->vec3();
}

}  // namespace

void parse_bodies(const Field& root, ParseContext& ctx) {
  const Field list = root.at("bodies");
  std::set<std::string> names{"ground"};
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Field b = list.at(i);
    if (!b.is_object()) b.fail("expected an object");
    const std::string name = b.at("name").string();
    if (name.empty()) b.at("name").fail("must not be empty");
    if (!names.insert(name).second) b.at("name").fail("duplicate body name '" + name + "'" + (name == "ground" ? " (ground always exists)" : ""));
    const std::string type = b.at("type").string();
    if (type == "rigid") {
      b.allow_only({"name", "type", "mass", "com", "inertia", "position", "orientation", "velocity", "angular_velocity",
                    "visual"});
      // The surface ffr-sim --vtk draws (the integration never reads it): checked here for its form.
      if (auto v = b.find("visual")) {
        const std::string file = v->string();
        const auto dot = file.rfind('.');
        std::string ext = dot == std::string::npos ? "" : file.substr(dot);
        for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        if (ext != ".stl") v->fail("must name an STL file (.stl, ASCII or binary), not '" + file + "'");
      }
      const double mass = b.at("mass").positive();
      const auto pos = b.find("position");
      const auto com = b.find("com");
      const Vector3d position = pos ? pos->vec3() : com ? com->vec3() : Vector3d::Zero();
      const Vector3d c = com ? com->vec3() : position;
      Body body = make_rigid_body(name, mass, c, b.at("inertia").mat3(), position, orientation(b.find("orientation")),
                                  ctx.file, b.path());
      initial_motion(b, body);
      ctx.model.bodies.push_back(std::move(body));
    } else if (type == "flexible") {
      b.allow_only({"name", "type", "sid", "position", "orientation", "damping", "stiffening", "velocity",
                       "angular_velocity", "modal_coordinates", "modal_velocities"});
      const Field sidf = b.at("sid");
      const formats::Sid sid = read_sid_for(sidf, ctx.base, ctx.model.notes);
      if (sid.units_length != "m" || sid.units_mass != "kg" || sid.units_time != "s")
        throw ModelError(ctx.base.empty() ? sidf.string() : (ctx.base / sidf.string()).string(), "/@units_length",
                         "only SI SID files are supported (found " + sid.units_length + ", " + sid.units_mass + ", " +
                             sid.units_time + ")");
      std::optional<double> ratio;
      if (auto d = b.find("damping")) {
        d->allow_only({"ratio"});
        ratio = d->at("ratio").non_negative();
        if (*ratio >= 1) d->at("ratio").fail("must be below 1 (critical damping)");
      }
      const bool stiff = b.has("stiffening") ? b.at("stiffening").boolean() : true;
      Body body = make_flexible_body(name, sid, b.has("position") ? b.at("position").vec3() : Vector3d::Zero(),
                                     orientation(b.find("orientation")), ratio, stiff, (ctx.base / sidf.string()).string(),
                                     ctx.file + ": " + sidf.path(), &ctx.model.notes);
      body.source = sidf.string();
      ctx.model.sid_files.push_back((ctx.base / sidf.string()).string());
      initial_motion(b, body);
      if (auto f = b.find("modal_coordinates")) body.y0 = f->vector(body.nq);
      if (auto f = b.find("modal_velocities")) body.yd0 = f->vector(body.nq);
      ctx.model.bodies.push_back(std::move(body));
    } else if (type == "beam") {
      parse_beam(b, name, ctx);
    } else if (type == "plate") {
      ctx.model.bodies.push_back(parse_plate(b, name, ctx));
    } else {
      b.at("type").fail("unknown body type '" + type + "' (expected rigid, flexible, beam or plate)");
    }
  }
}

}  // namespace ffr::runtime::detail
