#pragma once
// Strict reading of the model file: every access names its field ("bodies[1].mass") and every
// failure throws ModelError(file, field, what). Unknown keys are refused (a typo must not be
// silently ignored); keys starting with '_' and "comment"/"description" are allowed anywhere.

#include "ffr/runtime/errors.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace ffr::runtime::detail {

class Field {
 public:
  Field(const nlohmann::json& j, std::string file, std::string path) : j_(&j), file_(std::move(file)), path_(std::move(path)) {}

  const nlohmann::json& json() const { return *j_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  [[noreturn]] void fail(const std::string& what) const { throw ModelError(file_, path_, what); }

  bool has(const char* key) const { return j_->is_object() && j_->contains(key); }
  Field at(const char* key) const;                        ///< required member
  std::optional<Field> get(const char* key) const;        ///< optional member
  Field at(std::size_t i) const;                          ///< array element
  std::size_t size() const;                               ///< array length (fails if not an array)

  void expect_object(std::initializer_list<const char*> allowed) const;
  double number() const;                                  ///< finite
  double positive() const;
  double nonnegative() const;
  int integer() const;
  bool boolean() const;
  std::string string() const;
  Eigen::Vector3d vec3() const;
  Eigen::Matrix3d mat3() const;                           ///< rows as given
  Eigen::VectorXd vector(int n = -1) const;               ///< n < 0: any length >= 1
  Eigen::MatrixXd matrix(int cols) const;                 ///< rows of `cols` numbers

 private:
  const nlohmann::json* j_;
  std::string file_, path_;
};

}  // namespace ffr::runtime::detail
