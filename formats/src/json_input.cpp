#include "ffr/formats/json_input.hpp"

#include "ffr/formats/text_file.hpp"

#include <cmath>
#include <climits>
#include <set>
#include <vector>

namespace ffr::formats {
namespace {

// Deeper input is no part or model file, and the recursion of nlohmann's dump (the short text
// of a value in messages) overflowed the stack on 70 000 nested brackets.
constexpr std::size_t kMaxDepth = 64;

// Where the parser is (for messages): one frame per open object or array, with the member or
// element being read, and an object's keys so far.
struct Frame {
  bool array = false;
  long index = -1;
  std::string key;
  std::set<std::string> keys;
};

std::string frames_path(const std::vector<Frame>& frames) {
  std::string p;
  for (const Frame& f : frames) {
    if (f.array && f.index >= 0) p += "[" + std::to_string(f.index) + "]";
    if (!f.array && !f.key.empty()) p += (p.empty() ? "" : ".") + f.key;
  }
  return p;
}

}  // namespace

std::string JsonNode::describe() const {
  std::string s = j_->dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

void JsonNode::fail(const std::string& what) const {
  throw FormatError(*file_, path_.empty() ? "(top level)" : path_, what);
}

JsonNode JsonNode::at(const std::string& key) const {
  if (!j_->is_object()) fail("expected an object, found " + describe());
  auto it = j_->find(key);
  const std::string p = path_.empty() ? key : path_ + "." + key;
  if (it == j_->end()) throw FormatError(*file_, p, "missing required field");
  return JsonNode(&*it, p, file_);
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
  if (!j_->is_object()) fail("expected an object, found " + describe());
  auto it = j_->find(key);
  if (it == j_->end() || it->is_null()) return std::nullopt;
  return JsonNode(&*it, path_.empty() ? key : path_ + "." + key, file_);
}

std::vector<JsonNode> JsonNode::items() const {
  if (!j_->is_array()) fail("expected an array, found " + describe());
  std::vector<JsonNode> out;
  for (std::size_t i = 0; i < j_->size(); ++i)
    out.emplace_back(&(*j_)[i], path_ + "[" + std::to_string(i) + "]", file_);
  return out;
}

std::size_t JsonNode::size() const {
  if (!j_->is_array()) fail("expected an array, found " + describe());
  return j_->size();
}

JsonNode JsonNode::at(std::size_t i) const {
  if (i >= size()) fail("has no element " + std::to_string(i));
  return JsonNode(&(*j_)[i], path_ + "[" + std::to_string(i) + "]", file_);
}

void JsonNode::allow_only(std::initializer_list<const char*> keys) const {
  if (!j_->is_object()) fail("expected an object, found " + describe());
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    const std::string& key = it.key();
    if (key.rfind('_', 0) == 0 || key == "comment" || key == "description") continue;  // annotations
    bool ok = false;
    for (const char* k : keys) ok = ok || key == k;
    if (!ok) {
      std::string list;
      for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
      throw FormatError(*file_, path_.empty() ? it.key() : path_ + "." + it.key(),
                        "unknown field (allowed here: " + list + ")");
    }
  }
}

static_assert(kMaxInputMagnitude == 1e30, "number() says 1e30 in its message");

double JsonNode::number() const {
  if (!j_->is_number()) fail("expected a number, found " + describe());
  const double v = j_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  if (std::abs(v) > kMaxInputMagnitude) fail("magnitude beyond 1e30, found " + describe() + " (no value in SI units is that large)");
  return v;
}

double JsonNode::positive() const {
  const double v = number();
  if (!(v > 0)) fail("expected a positive number, found " + describe());
  return v;
}

double JsonNode::non_negative() const {
  const double v = number();
  if (v < 0) fail("expected a number >= 0, found " + describe());
  return v;
}

long long JsonNode::integer() const {
  if (j_->is_number_unsigned()) {
    if (j_->get<unsigned long long>() > static_cast<unsigned long long>(LLONG_MAX)) fail("integer out of range, found " + describe());
    return j_->get<long long>();
  }
  if (j_->is_number_integer()) return j_->get<long long>();
  if (!j_->is_number_float() || std::floor(j_->get<double>()) != j_->get<double>()) fail("expected an integer, found " + describe());
  const double v = j_->get<double>();
  // A double beyond 2^53 is no exact integer, and one beyond the range of long long would make
  // the conversion undefined (1e19 landed on 0).
  if (std::abs(v) > 9007199254740992.0) fail("integer out of range, found " + describe());
  return static_cast<long long>(v);
}

int JsonNode::small_integer() const {
  const long long v = integer();
  if (v < -1000000000LL || v > 1000000000LL) fail("integer out of range, found " + describe());
  return static_cast<int>(v);
}

bool JsonNode::boolean() const {
  if (!j_->is_boolean()) fail("expected true or false, found " + describe());
  return j_->get<bool>();
}

std::string JsonNode::string() const {
  if (!j_->is_string()) fail("expected a string, found " + describe());
  return j_->get<std::string>();
}

std::vector<double> JsonNode::numbers() const {
  std::vector<double> out;
  for (const auto& n : items()) out.push_back(n.number());
  return out;
}

Eigen::VectorXd JsonNode::vector(int n) const {
  const std::size_t len = size();
  if (n >= 0 && len != static_cast<std::size_t>(n))
    fail("expected " + std::to_string(n) + " numbers, found " + std::to_string(len));
  if (n < 0 && len == 0) fail("must not be empty");
  Eigen::VectorXd v(static_cast<Eigen::Index>(len));
  for (std::size_t i = 0; i < len; ++i) v(static_cast<Eigen::Index>(i)) = at(i).number();
  return v;
}

Eigen::MatrixXd JsonNode::matrix(int cols) const {
  const std::size_t rows = size();
  if (rows == 0) fail("must not be empty");
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), cols);
  for (std::size_t r = 0; r < rows; ++r) {
    const JsonNode row = at(r);
    if (cols == 1 && row.is_number())
      m(static_cast<Eigen::Index>(r), 0) = row.number();
    else
      m.row(static_cast<Eigen::Index>(r)) = row.vector(cols).transpose();
  }
  return m;
}

Eigen::Vector3d JsonNode::vec3() const {
  if (!j_->is_array() || j_->size() != 3) fail("expected [x, y, z], found " + describe());
  const auto v = numbers();
  return {v[0], v[1], v[2]};
}

Eigen::Matrix3d JsonNode::mat3() const {
  if (!j_->is_array() || j_->size() != 3) fail("expected a 3x3 matrix [[..],[..],[..]], found " + describe());
  Eigen::Matrix3d m;
  const auto rows = items();
  for (int r = 0; r < 3; ++r) m.row(r) = rows[r].vec3().transpose();
  return m;
}

double JsonNode::number_or(const std::string& key, double dflt) const {
  auto n = find(key);
  return n ? n->number() : dflt;
}

bool JsonNode::boolean_or(const std::string& key, bool dflt) const {
  auto n = find(key);
  return n ? n->boolean() : dflt;
}

std::string JsonNode::string_or(const std::string& key, const std::string& dflt) const {
  auto n = find(key);
  return n ? n->string() : dflt;
}

JsonDocument JsonDocument::parse(const std::string& text, const std::string& display_name) {
  JsonDocument d;
  d.file_ = std::make_shared<const std::string>(display_name);
  std::vector<Frame> frames;
  // Refuses, while parsing, nesting beyond kMaxDepth and a key given twice in one object (the
  // library would keep the last silently).
  auto watch = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    auto next_element = [&] {
      if (!frames.empty() && frames.back().array) ++frames.back().index;
    };
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        next_element();
        if (frames.size() >= kMaxDepth)
          throw FormatError(display_name, frames_path(frames), "nested deeper than " + std::to_string(kMaxDepth) + " levels");
        frames.push_back(Frame{event == Event::array_start, -1, {}, {}});
        break;
      case Event::key:
        frames.back().key = parsed.get<std::string>();
        if (!frames.back().keys.insert(frames.back().key).second)
          throw FormatError(display_name, frames_path(frames), "given twice in the same object");
        break;
      case Event::value:
        next_element();
        break;
      case Event::object_end:
      case Event::array_end:
        frames.pop_back();
        break;
    }
    return true;
  };
  try {
    d.json_ = nlohmann::json::parse(text, watch);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the error; turn it into line and column.
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
    }
    std::string msg = e.what();
    const auto pos = msg.find("parse error");
    if (pos != std::string::npos) msg = msg.substr(pos);
    throw FormatError(display_name, "", "malformed JSON at line " + std::to_string(line) + ", column " +
                                            std::to_string(col) + " (" + msg + ")");
  } catch (const nlohmann::json::exception& e) {
    // e.g. "number overflow parsing '1e999'": a number that is not a finite double.
    std::string msg = e.what();
    const auto pos = msg.find("] ");
    throw FormatError(display_name, "", "not a finite number in the JSON text: " +
                                            (pos == std::string::npos ? msg : msg.substr(pos + 2)));
  }
  return d;
}

JsonDocument JsonDocument::load(const std::filesystem::path& path) {
  return parse(read_text_file(path), path.string());
}

}  // namespace ffr::formats
