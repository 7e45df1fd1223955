#pragma once
// A force along the line of two marker points (spring-dampers, friction dampers): tension T,
// +T n on point 1 and -T n on point 2 (n the unit vector from 1 to 2). The element gives T and
// its derivatives dT/dl, dT/dl_dot; these add the generalized forces and their exact tangents.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime::detail {

struct LineState {
  Vector3d d, dd, n;
  double l = 0, ldot = 0;
  /// A line squeezed to a point has no direction: the element exerts nothing there (the model
  /// loader refuses elements whose ends coincide initially unless their free length is 0).
  bool valid = false;
};

LineState line_state(const Model& model, int m1, int m2, const Data& data);
/// Q += the generalized forces of tension T; ends (optional): each end's over its body's 12
/// frame columns (spring_forces).
void add_line_force(const Model& model, int m1, int m2, const LineState& st, double T, Data& data,
                    Eigen::Matrix<double, 12, 2>* ends = nullptr);
/// K, C += -dQ/dq, -dQ/dq_dot of a tension T(l, l_dot) with dT/dl = kl and dT/dl_dot = cl.
void add_line_tangents(const Model& model, int m1, int m2, const LineState& st, double T, double kl, double cl,
                       Data& data);

}  // namespace ffr::runtime::detail
