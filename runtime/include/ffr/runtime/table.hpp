#pragma once
// A table of samples interpolated per component: piecewise linear, monotone cubic (PCHIP) or
// natural cubic spline (MODEL_FILE.md "Tables", FORMULATION.md section 10).
//
// Why three kinds: a load or a characteristic must never exceed its samples (a ramp-and-hold
// load through a spline overshoots and drives a spring past its static deflection), so their
// default is linear; a motion needs a velocity and an acceleration (the acceleration enters the
// index-3 constraint's bias), so its default is PCHIP (Fritsch & Carlson): C1, bounded by its
// samples between them and monotone where they are, its acceleration piecewise continuous. The
// natural spline is C2 but overshoots; it is kept as an option. Beyond its ends every table is
// continued linearly with its end slope (so a held last value stays held). One sample is a
// constant; two samples a straight line whatever the kind.

#include <Eigen/Core>

namespace ffr::runtime {

enum class Interpolation { Linear, Pchip, Spline };
const char* to_string(Interpolation k);

class Table {
 public:
  Table() = default;
  /// t strictly increasing (checked by the caller, which knows the file and field); values is
  /// [len(t), ncomp].
  Table(Eigen::VectorXd t, Eigen::MatrixXd values, Interpolation kind = Interpolation::Spline);

  int components() const { return static_cast<int>(v_.cols()); }
  bool empty() const { return t_.size() == 0; }
  const Eigen::VectorXd& times() const { return t_; }
  const Eigen::MatrixXd& values() const { return v_; }
  Interpolation kind() const { return kind_; }

  /// Value and first two derivatives of component c at t. Allocation-free. Where the second
  /// derivative jumps (a knot of a linear or PCHIP table) the right-hand one is returned.
  void eval(double t, int c, double& value, double& d1, double& d2) const;
  double value(double t, int c) const {
    double v, d1, d2;
    eval(t, c, v, d1, d2);
    return v;
  }
  /// The exact integral of component c from the first sample time to t (t below the first
  /// time gives the negative integral of the linear continuation). Allocation-free.
  double integral(double t, int c) const;

 private:
  Eigen::VectorXd t_;
  Eigen::MatrixXd v_;   ///< [n, ncomp]
  /// Per knot: the spline's second derivatives, or PCHIP's first derivatives, [n, ncomp]
  /// (zero for a linear table).
  Eigen::MatrixXd m_;
  Interpolation kind_ = Interpolation::Spline;
  /// Segment i's cubic on [t_i, t_i+1] as value, slope and curvature at any point: shared by
  /// eval and integral.
  void segment(Eigen::Index i, double t, int c, double& value, double& d1, double& d2) const;
  double segment_integral(Eigen::Index i, double t, int c) const;  ///< from t_i to t in segment i
  void slopes(Eigen::Index i, int c, double& s0, double& s1) const;  ///< segment i's end slopes
  Eigen::MatrixXd cum_;  ///< integral from t_0 to each knot, [n, ncomp]
};

}  // namespace ffr::runtime
