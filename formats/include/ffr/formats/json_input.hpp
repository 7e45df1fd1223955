#pragma once
// Reading user JSON input (part files, model files) with errors that name the file and the
// field: "part.json: materials[0].E: expected a positive number, found -7e10". Every accessor
// validates; unknown keys can be refused so a typo is not silently ignored. Annotation keys
// ("comment", "description", and any key starting with '_') are allowed in every object.

#include "ffr/formats/h5.hpp"  // FormatError

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ffr::formats {

class JsonNode {
 public:
  JsonNode(const nlohmann::json* j, std::string path, std::shared_ptr<const std::string> file)
      : j_(j), path_(std::move(path)), file_(std::move(file)) {}

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  const nlohmann::json& raw() const { return *j_; }

  bool is_object() const { return j_->is_object(); }
  bool is_array() const { return j_->is_array(); }
  bool is_string() const { return j_->is_string(); }
  bool is_number() const { return j_->is_number(); }
  bool has(const std::string& key) const { return j_->is_object() && j_->contains(key); }

  /// Required member of an object.
  JsonNode at(const std::string& key) const;
  /// Optional member of an object.
  std::optional<JsonNode> find(const std::string& key) const;
  /// Elements of an array (fails if not an array).
  std::vector<JsonNode> items() const;
  /// Length of an array (fails if not an array).
  std::size_t size() const;
  /// Element i of an array.
  JsonNode at(std::size_t i) const;
  /// Refuses members other than these and the annotation keys (catches typos such as
  /// "thikness").
  void allow_only(std::initializer_list<const char*> keys) const;

  double number() const;           ///< finite number of magnitude at most 1e30
  double positive() const;         ///< finite and > 0
  double non_negative() const;     ///< finite and >= 0
  long long integer() const;       ///< integral number
  int small_integer() const;       ///< integral number within +-1e9 (a count, an index, a version)
  bool boolean() const;
  std::string string() const;
  Eigen::Vector3d vec3() const;    ///< [x, y, z]
  Eigen::Matrix3d mat3() const;    ///< [[..],[..],[..]]
  std::vector<double> numbers() const;
  Eigen::VectorXd vector(int n = -1) const;  ///< n numbers (n < 0: at least one)
  Eigen::MatrixXd matrix(int cols) const;    ///< rows of `cols` numbers (cols = 1: plain numbers too)

  // Optional-with-default helpers.
  double number_or(const std::string& key, double dflt) const;
  bool boolean_or(const std::string& key, bool dflt) const;
  std::string string_or(const std::string& key, const std::string& dflt) const;

  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::string describe() const;  // short text of the value for messages
  const nlohmann::json* j_;
  std::string path_;
  std::shared_ptr<const std::string> file_;
};

/// A parsed JSON document. Malformed JSON (including NaN/Infinity literals) is a FormatError
/// naming the file, line and column; so is a number too large for a double (1e999). Nesting
/// deeper than 64 levels and a key given twice in one object are refused with their path.
class JsonDocument {
 public:
  static JsonDocument load(const std::filesystem::path& path);
  static JsonDocument parse(const std::string& text, const std::string& display_name);
  JsonNode root() const { return JsonNode(&json_, "", file_); }

 private:
  nlohmann::json json_;
  std::shared_ptr<const std::string> file_;
};

}  // namespace ffr::formats
