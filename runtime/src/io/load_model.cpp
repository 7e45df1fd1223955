// The model file: top level, gravity, solver settings; sections are parsed in their own files.
#include "ffr/runtime/load.hpp"

#include "parse.hpp"
#include "ffr/runtime/step_control.hpp"
#include "../number_text.hpp"

#include <algorithm>
#include <cmath>

namespace ffr::runtime {
namespace detail {

int body_ref(const Field& f, const Model& m) {
  const std::string n = f.string();
  const int b = m.find_body(n);
  // A geometrically exact beam is named by its first node's body; its nodes pick the others (node_ref).
  for (const GeBeam& g : m.ge_beams)
    if (g.name == n) return g.node_bodies.front();
  if (b == -2) {
    std::string known = "ground";
    for (const auto& body : m.bodies) known += ", " + body.name;
    for (const GeBeam& g : m.ge_beams) known += ", " + g.name;
    f.fail("unknown body '" + n + "' (bodies: " + known + ")");
  }
  return b;
}

Vector3d unit_axis(const Field& f) {
  const Vector3d a = f.vec3();
  // Scaled first where the squared norm would underflow or overflow (only there: scaling moves
  // the last bit of the direction, and with it the results of sensitive models).
  const double largest = a.cwiseAbs().maxCoeff();
  if (!(largest > 0)) f.fail("must not be the zero vector");
  return largest > 1e-150 && largest < 1e150 ? a.normalized() : Vector3d((a / largest).normalized());
}

Matrix3d triad(const Vector3d& axis) {
  const Vector3d e = axis.normalized();
  int k = 0;
  e.cwiseAbs().minCoeff(&k);
  Vector3d helper = Vector3d::Zero();
  helper(k) = 1;
  const Vector3d f = (helper - helper.dot(e) * e).normalized();
  Matrix3d E;
  E << e, f, e.cross(f);
  return E;
}

Interpolation interpolation(const Field& f) {
  const std::string s = f.string();
  if (s == "linear") return Interpolation::Linear;
  if (s == "pchip") return Interpolation::Pchip;
  if (s == "spline") return Interpolation::Spline;
  f.fail("unknown interpolation '" + s + "' (expected linear, pchip or spline)");
}

Table parse_table(const Field& f, int ncomp, Interpolation default_kind) {
  f.allow_only({"t", "value", "interpolation"});
  const Interpolation kind = f.has("interpolation") ? interpolation(f.at("interpolation")) : default_kind;
  const Eigen::VectorXd t = f.at("t").vector();
  const Field vf = f.at("value");
  const Eigen::MatrixXd v = vf.matrix(ncomp);
  if (v.rows() != t.size())
    vf.fail("has " + std::to_string(v.rows()) + " entries but t has " + std::to_string(t.size()));
  for (Eigen::Index i = 1; i < t.size(); ++i)
    if (!(t(i) > t(i - 1))) f.at("t").fail("times must be strictly increasing (entry " + std::to_string(i) + ")");
  return Table(t, v, kind);
}

// Refuses a run whose times are too far from zero for its steps (kMinStepInTimeSpacings).
void require_resolved_times(const Field& s, const SolverSettings& st, double step, const std::string& which) {
  const double least = time_resolution_step(st.start, st.end);
  if (step >= least) return;
  // The remedy is a start nearer to 0; a run from 0 this far has more steps than any run takes.
  const double t = std::max(std::abs(st.start), std::abs(st.end));
  s.at(st.start != 0 ? "start" : "end")
      .fail("times near " + fmt(t) + " s are resolved only to " + fmt(least / kMinStepInTimeSpacings) +
            " s (the spacing of doubles there), and " + which + ", " + fmt(step) + " s, spans fewer than " +
            fmt(kMinStepInTimeSpacings) + " of them (at least " + fmt(least) +
            " s): start the run nearer to t = 0, shifting its tables and motions alike");
}

// The integrator (FORMULATION.md section 9) and "step": a fixed step, or "auto" with its own
// keys, each refused with the other (a key that would be silently ignored is a wrong answer).
void parse_scheme(const Field& s, SolverSettings& st) {
  if (auto f = s.find("integrator")) {
    const std::string v = f->string();
    if (v == "trapezoidal") st.integrator = Integrator::Trapezoidal;
    else if (v == "generalized_alpha") st.integrator = Integrator::GeneralizedAlpha;
    else f->fail("unknown integrator '" + v + "' (trapezoidal, generalized_alpha)");
  }
  if (auto f = s.find("spectral_radius")) {
    if (st.integrator != Integrator::GeneralizedAlpha) f->fail("is a setting of \"integrator\": \"generalized_alpha\"");
    st.spectral_radius = f->number();
    if (!(st.spectral_radius >= 0 && st.spectral_radius <= 1)) f->fail("must be in [0, 1] (1: no numerical damping)");
  } else if (st.integrator == Integrator::GeneralizedAlpha) {
    s.fail("\"integrator\": \"generalized_alpha\" needs \"spectral_radius\" in [0, 1]");
  }
  const Field step = s.at("step");
  st.adaptive = step.is_string();
  if (st.adaptive && step.string() != "auto") step.fail("must be a step in seconds or \"auto\"");
  const double run = st.end - st.start;
  if (!st.adaptive) {
    for (const char* k : {"rtol", "atol", "output_interval", "max_step"})
      if (auto f = s.find(k)) f->fail(std::string("is a setting of \"step\": \"auto\" (a fixed step was given)"));
    st.step = step.positive();
    return;
  }
  if (auto f = s.find("output_every")) f->fail("is a setting of a fixed step; with \"step\": \"auto\" use \"output_interval\" [s]");
  if (auto f = s.find("rtol")) st.rtol = f->positive();
  if (auto f = s.find("atol")) st.atol = f->positive();
  if (st.rtol < 1e-14) s.at("rtol").fail("is below what double precision can reach (1e-14)");
  st.output_interval = run / 100;
  if (auto f = s.find("output_interval")) {
    st.output_interval = f->positive();
    if (st.output_interval > run) f->fail("is longer than the run (end - start)");
    if (run / st.output_interval > 1e9) f->fail("gives more than 1e9 samples");
  }
  if (auto f = s.find("max_step")) {
    st.max_step = f->positive();
    // Below the error control's smallest step every step would be refused as too small.
    const double fraction = StepControlLimits{}.min_step_fraction;
    if (st.max_step < fraction * run)
      f->fail("is below the smallest step the error control takes, " + fmt(fraction * run) + " s (" + fmt(fraction) +
              " of the run)");
  }
  // Every step lands on the output times, so none is longer than the output interval.
  const double longest = st.max_step > 0 ? std::min(st.max_step, st.output_interval) : st.output_interval;
  require_resolved_times(s, st, longest, "the longest step this run takes (max_step or output_interval)");
  // The first step tried: a guess the error estimate corrects within the first steps.
  st.step = 1e-2 * longest;
}

// The constraints' tolerance, in model lengths: below the coordinates' rounding no projection or
// Newton step can meet it (1e-300 failed the first step asking for a smaller one); above
// kMaxConstraintTolerance the violations it leaves cost accuracy.
double constraint_tolerance(const Field& f) {
  const double v = f.positive();
  if (v < kRoundOffTolerance)
    f.fail("is below what double precision can reach (" + fmt(kRoundOffTolerance) + " of the model length)");
  if (v > kMaxConstraintTolerance)
    f.fail("must be at most " + fmt(kMaxConstraintTolerance) +
           " of the model length: a looser one costs accuracy (the default 1e-12; FORMULATION.md section 9)");
  return v;
}

// The augmented-Lagrangian penalty: any positive value converges (a small one in more
// iterations), but above kMaxPenalty the constraint forces' rounding costs accuracy.
double penalty(const Field& f) {
  const double v = f.positive();
  if (v > kMaxPenalty)
    f.fail("must be at most " + fmt(kMaxPenalty) + ": above it the rounding of the constraint forces costs accuracy "
           "(the default 1e4 suits most models; FORMULATION.md section 9)");
  return v;
}

void parse_solver(const Field& root, ParseContext& ctx) {
  const Field s = root.at("solver");
  s.allow_only({"start", "end", "step", "output_every", "tolerance", "newton_tolerance", "max_iterations", "penalty", "reuse_jacobian",
                "eliminate_driven_bodies", "integrator", "spectral_radius", "rtol", "atol", "output_interval", "max_step",
                "analysis", "initial_equilibrium", "formulation"});
  SolverSettings& st = ctx.model.settings;
  if (auto f = s.find("start")) st.start = f->number();
  // FORMULATION.md 18; what "relative" cannot run is refused when the model is finalized.
  if (auto f = s.find("formulation")) {
    const std::string v = f->string();
    if (v == "absolute") st.formulation = Formulation::Absolute;
    else if (v == "relative") st.formulation = Formulation::Relative;
    else if (v == "auto") st.formulation = Formulation::Auto;
    else f->fail("unknown formulation '" + v + "' (absolute, relative, auto)");
  }
  if (auto f = s.find("analysis")) {
    const std::string v = f->string();
    if (v == "static") st.static_analysis = true;
    else if (v != "dynamic") f->fail("unknown analysis '" + v + "' (dynamic, static)");
  }
  if (st.static_analysis) {
    // One equilibrium at "start": the keys of a time integration would be ignored, so they are refused.
    for (const char* k : {"end", "step", "output_every", "integrator", "spectral_radius", "rtol", "atol", "output_interval",
                          "max_step", "initial_equilibrium"})
      if (auto f = s.find(k))
        f->fail("is a setting of a dynamic run (\"analysis\": \"static\" solves the equilibrium at \"start\" alone)");
    st.end = st.start;
    if (auto f = s.find("tolerance")) st.tolerance = constraint_tolerance(*f);
    if (auto f = s.find("newton_tolerance")) st.newton_tolerance = f->positive();
    if (auto f = s.find("penalty")) st.penalty = penalty(*f);
    if (auto f = s.find("eliminate_driven_bodies")) st.eliminate_driven = f->boolean();
    if (auto f = s.find("max_iterations")) f->fail("is a setting of a dynamic run's steps");
    if (auto f = s.find("reuse_jacobian")) f->fail("is a setting of a dynamic run's steps");
    return;
  }
  if (auto f = s.find("initial_equilibrium")) st.initial_equilibrium = f->boolean();
  st.end = s.at("end").number();
  if (!(st.end > st.start)) s.at("end").fail("must be after the start time");
  parse_scheme(s, st);
  if (!st.adaptive) {
    const double n = (st.end - st.start) / st.step;
    if (n > 1e9) s.at("step").fail("gives more than 1e9 steps");
    // A step longer than the run rounded to no step at all below (n ~ 0 is "whole").
    if (n < 0.5) s.at("step").fail("is longer than the run (end - start)");
    if (std::abs(n - std::round(n)) > 1e-6 * std::max(1.0, n))
      s.at("step").fail("the run (end - start) is not a whole number of steps");
    require_resolved_times(s, st, st.step, "the step");
  }
  if (auto f = s.find("output_every")) {
    st.output_every = f->small_integer();
    if (st.output_every < 1) f->fail("must be at least 1");
  }
  if (auto f = s.find("tolerance")) st.tolerance = constraint_tolerance(*f);
  if (auto f = s.find("newton_tolerance")) st.newton_tolerance = f->positive();
  if (auto f = s.find("max_iterations")) {
    st.max_iterations = f->small_integer();
    if (st.max_iterations < 1) f->fail("must be at least 1");
    // Newton converges in a few iterations or stalls (at round-off, or oscillating): a bound of
    // up to 1e9 let a step that stalls run for hours instead of failing with its message.
    if (st.max_iterations > kMaxNewtonIterations)
      f->fail("must be at most " + std::to_string(kMaxNewtonIterations) + " (found " + std::to_string(st.max_iterations) +
              "): a step that has not converged by then does not; a smaller step is the remedy");
  }
  if (auto f = s.find("penalty")) st.penalty = penalty(*f);
  // Refused: a tangent kept over steps converges to the same tolerance only with honest
  // (contraction-measured) acceptance, and even then it does not keep the integrator's accuracy
  // (Andrews' squeezing mechanism ends 1e-5 rad away from the default, far above its Richardson-
  // extrapolated error), nor does it pay (tools/bench/runtime_step/RESULTS.md). `false` is kept
  // for files that spell the default out.
  if (auto f = s.find("reuse_jacobian"))
    if (f->boolean())
      f->fail("true is not supported: a tangent kept over steps does not keep the integrator's accuracy; "
              "remove the key (a fresh tangent every step is the default)");
  if (auto f = s.find("eliminate_driven_bodies")) st.eliminate_driven = f->boolean();
}

}  // namespace detail

namespace {

// A time table whose samples all lie outside the run is read only by its extrapolation with the
// end slope (MODEL_FILE.md "Tables"): legal, but most often times in another unit (ms) or a run
// that starts elsewhere, so it is a note.
void note_tables_outside_the_run(Model& m) {
  const double start = m.settings.start, end = m.settings.end;
  const auto check = [&](const Table& table, const std::string& what) {
    const Eigen::VectorXd& t = table.times();
    if (t.size() < 2 || (t[t.size() - 1] >= start && t[0] <= end)) return;
    m.notes.push_back(what + ": its samples, t = " + num(t[0]) + " .. " + num(t[t.size() - 1]) + " s, all lie outside the run (" +
                      num(start) + " .. " + num(end) + " s): it is extrapolated over the whole run with its end slope");
  };
  for (const PointLoad& l : m.loads) check(l.table, (l.torque ? "point_torque '" : "point_force '") + l.name + "'");
  for (const Motion& mo : m.motions)
    check(mo.table, "the " + std::string(mo.speed ? "speed" : "table") + " of the motion of joint '" + m.joints[mo.joint].name + "'");
}

Model parse_document(const formats::JsonDocument& doc, const std::filesystem::path& base_dir, const std::string& name) {
  Model m;
  m.source = name;
  detail::ParseContext ctx{name, base_dir, m};
  const detail::Field root = doc.root();
  root.allow_only({"format_version", "units", "gravity", "bodies", "joints", "forces", "motions", "solver", "outputs", "roads"});
  if (auto f = root.find("format_version"))
    if (f->small_integer() != 1) f->fail("unsupported format_version (this build reads 1)");
  if (auto f = root.find("units")) {
    f->allow_only({"length", "mass", "time"});
    for (const char* k : {"length", "mass", "time"})
      if (auto u = f->find(k)) {
        const std::string s = u->string();
        const bool si = (std::string(k) == "length" && s == "m") || (std::string(k) == "mass" && s == "kg") ||
                        (std::string(k) == "time" && s == "s");
        if (!si) u->fail("only SI units are supported (m, kg, s)");
      }
  }
  if (auto g = root.find("gravity")) m.gravity = g->vec3();
  detail::parse_solver(root, ctx);
  detail::parse_bodies(root, ctx);
  detail::parse_joints(root, ctx);
  detail::parse_roads(root, ctx);
  detail::parse_forces(root, ctx);
  detail::check_bodies_can_turn(root, ctx);
  detail::check_beam_attachments(root, ctx);
  detail::check_plate_attachments(root, ctx);
  detail::parse_motions(root, ctx);
  note_tables_outside_the_run(m);
  detail::parse_outputs(root, ctx);
  finalize(m);
  return m;
}

// The model file's own errors come as FormatError from the JSON reader; the runtime reports
// bad input as ModelError (file, field, what), which the C API and ffr-sim map to their codes.
template <class Read>
Model as_model_errors(Read&& read) {
  try {
    return read();
  } catch (const formats::FormatError& e) {
    throw ModelError(e.file(), e.object(), e.detail());
  }
}

}  // namespace

Model parse_model(const std::string& text, const std::filesystem::path& base_dir, const std::string& name) {
  return as_model_errors([&] { return parse_document(formats::JsonDocument::parse(text, name), base_dir, name); });
}

Model load_model(const std::filesystem::path& path) {
  return as_model_errors(
      [&] { return parse_document(formats::JsonDocument::load(path), path.parent_path(), path.string()); });
}

}  // namespace ffr::runtime
