#pragma once
// A time table interpolated with a natural cubic spline, per component.
//
// Why a natural spline: motions must have continuous velocity *and* acceleration (the
// acceleration enters the index-3 constraint and the acceleration projection), and the
// natural end condition (zero second derivative) lets the table be continued linearly beyond
// its ends without breaking C2 continuity. One point is a constant, two points a straight line.

#include <Eigen/Core>

namespace ffr::runtime {

class Table {
 public:
  Table() = default;
  /// t strictly increasing (checked by the caller, which knows the file and field); values is
  /// [len(t), ncomp].
  Table(Eigen::VectorXd t, Eigen::MatrixXd values);

  int components() const { return static_cast<int>(v_.cols()); }
  bool empty() const { return t_.size() == 0; }
  const Eigen::VectorXd& times() const { return t_; }

  /// Value and first two derivatives of component c at time t. Allocation-free.
  void eval(double t, int c, double& value, double& d1, double& d2) const;
  double value(double t, int c) const {
    double v, d1, d2;
    eval(t, c, v, d1, d2);
    return v;
  }

 private:
  Eigen::VectorXd t_;
  Eigen::MatrixXd v_;   ///< [n, ncomp]
  Eigen::MatrixXd m_;   ///< second derivatives at the knots, [n, ncomp]
};

}  // namespace ffr::runtime
