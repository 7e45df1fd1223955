#include "json_reader.hpp"

#include <cmath>
#include <cstring>

namespace ffr::runtime::detail {
namespace {

const char* type_name(const nlohmann::json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

}  // namespace

Field Field::at(const char* key) const {
  if (!j_->is_object()) fail(std::string("expected an object, found ") + type_name(*j_));
  if (!j_->contains(key)) throw ModelError(file_, path_.empty() ? key : path_ + "." + key, "missing");
  return Field((*j_)[key], file_, path_.empty() ? key : path_ + "." + key);
}

std::optional<Field> Field::get(const char* key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

Field Field::at(std::size_t i) const { return Field((*j_)[i], file_, path_ + "[" + std::to_string(i) + "]"); }

std::size_t Field::size() const {
  if (!j_->is_array()) fail(std::string("expected an array, found ") + type_name(*j_));
  return j_->size();
}

void Field::expect_object(std::initializer_list<const char*> allowed) const {
  if (!j_->is_object()) fail(std::string("expected an object, found ") + type_name(*j_));
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    const std::string& k = it.key();
    if (k.rfind('_', 0) == 0 || k == "comment" || k == "description") continue;
    bool ok = false;
    for (const char* a : allowed) ok = ok || k == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw ModelError(file_, path_.empty() ? k : path_ + "." + k, "unknown key (expected one of: " + list + ")");
    }
  }
}

double Field::number() const {
  if (!j_->is_number()) fail(std::string("expected a number, found ") + type_name(*j_));
  const double v = j_->get<double>();
  if (!std::isfinite(v)) fail("not a finite number");
  return v;
}

double Field::positive() const {
  const double v = number();
  if (!(v > 0)) fail("must be positive (found " + std::to_string(v) + ")");
  return v;
}

double Field::nonnegative() const {
  const double v = number();
  if (v < 0) fail("must not be negative (found " + std::to_string(v) + ")");
  return v;
}

int Field::integer() const {
  if (!j_->is_number_integer()) fail(std::string("expected an integer, found ") + type_name(*j_));
  const auto v = j_->get<long long>();
  if (v < -1000000000LL || v > 1000000000LL) fail("integer out of range");
  return static_cast<int>(v);
}

bool Field::boolean() const {
  if (!j_->is_boolean()) fail(std::string("expected true or false, found ") + type_name(*j_));
  return j_->get<bool>();
}

std::string Field::string() const {
  if (!j_->is_string()) fail(std::string("expected a string, found ") + type_name(*j_));
  return j_->get<std::string>();
}

Eigen::VectorXd Field::vector(int n) const {
  const std::size_t len = size();
  if (n >= 0 && len != static_cast<std::size_t>(n)) fail("expected " + std::to_string(n) + " numbers, found " + std::to_string(len));
  if (n < 0 && len == 0) fail("must not be empty");
  Eigen::VectorXd v(static_cast<Eigen::Index>(len));
  for (std::size_t i = 0; i < len; ++i) v(static_cast<Eigen::Index>(i)) = at(i).number();
  return v;
}

Eigen::Vector3d Field::vec3() const { return vector(3); }

Eigen::Matrix3d Field::mat3() const {
  if (size() != 3) fail("expected a 3x3 matrix (3 rows of 3 numbers)");
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) m.row(r) = at(static_cast<std::size_t>(r)).vec3().transpose();
  return m;
}

Eigen::MatrixXd Field::matrix(int cols) const {
  const std::size_t rows = size();
  if (rows == 0) fail("must not be empty");
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), cols);
  for (std::size_t r = 0; r < rows; ++r) {
    const Field row = at(r);
    if (cols == 1 && row.json().is_number())
      m(static_cast<Eigen::Index>(r), 0) = row.number();
    else
      m.row(static_cast<Eigen::Index>(r)) = row.vector(cols).transpose();
  }
  return m;
}

}  // namespace ffr::runtime::detail
