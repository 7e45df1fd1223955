// The reader of user JSON files (part files, model files): every refusal names the file and
// the field, annotation keys pass everywhere, and numbers a double cannot hold are refused.
#include "ffr/formats/json_input.hpp"
#include "ffr/formats/text_file.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

using ffr::formats::FormatError;
using ffr::formats::JsonDocument;

namespace {

// The message of the FormatError that f throws ("" if none).
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(JsonInput, AnnotationKeysPassAndTyposAreRefusedWithTheAllowedList) {
  const auto doc = JsonDocument::parse(
      R"({"comment": "c", "_note": 1, "solver": {"description": "d", "_x": [], "step": 1e-3, "stpe": 2}})", "m.json");
  const auto root = doc.root();
  EXPECT_NO_THROW(root.allow_only({"solver"}));
  const std::string msg = refusal([&] { root.at("solver").allow_only({"step"}); });
  EXPECT_NE(msg.find("m.json: solver.stpe: unknown field (allowed here: step)"), std::string::npos) << msg;
}

TEST(JsonInput, ArraysOfNumbersNameTheElement) {
  const auto doc = JsonDocument::parse(R"({"v": [1, 2, "x"], "m": [[1, 2], [3]], "e": [], "s": [4, 5]})", "f.json");
  const auto root = doc.root();
  EXPECT_EQ(root.at("s").vector(), Eigen::Vector2d(4, 5));
  EXPECT_EQ(root.at("s").matrix(1), Eigen::Vector2d(4, 5));
  EXPECT_EQ(root.at("s").size(), 2u);
  std::string msg = refusal([&] { root.at("v").vector(); });
  EXPECT_NE(msg.find("f.json: v[2]: expected a number"), std::string::npos) << msg;
  msg = refusal([&] { root.at("s").vector(3); });
  EXPECT_NE(msg.find("f.json: s: expected 3 numbers, found 2"), std::string::npos) << msg;
  msg = refusal([&] { root.at("m").matrix(2); });
  EXPECT_NE(msg.find("f.json: m[1]: expected 2 numbers, found 1"), std::string::npos) << msg;
  msg = refusal([&] { root.at("e").vector(); });
  EXPECT_NE(msg.find("f.json: e: must not be empty"), std::string::npos) << msg;
  msg = refusal([&] { root.at("s").at(2); });
  EXPECT_NE(msg.find("f.json: s: has no element 2"), std::string::npos) << msg;
}

TEST(JsonInput, IntegersOutOfRangeAndUnrepresentableNumbersAreRefused) {
  const auto doc = JsonDocument::parse(R"({"n": 3, "big": 5000000000, "half": 1.5})", "f.json");
  EXPECT_EQ(doc.root().at("n").small_integer(), 3);
  std::string msg = refusal([&] { doc.root().at("big").small_integer(); });
  EXPECT_NE(msg.find("f.json: big: integer out of range"), std::string::npos) << msg;
  msg = refusal([&] { doc.root().at("half").small_integer(); });
  EXPECT_NE(msg.find("f.json: half: expected an integer"), std::string::npos) << msg;
  msg = refusal([] { JsonDocument::parse(R"({"mass": 1e999})", "g.json"); });
  EXPECT_NE(msg.find("g.json: not a finite number in the JSON text"), std::string::npos) << msg;
}

TEST(JsonInput, TheMessageWithoutFileAndFieldIsKept) {
  const auto doc = JsonDocument::parse(R"({"E": -7})", "p.json");
  try {
    doc.root().at("E").positive();
    FAIL() << "a negative modulus passed";
  } catch (const FormatError& e) {
    EXPECT_EQ(e.file(), "p.json");
    EXPECT_EQ(e.object(), "E");
    EXPECT_EQ(e.detail(), "expected a positive number, found -7");
  }
}

TEST(JsonInput, DeepNestingAndRepeatedKeysAreRefusedWithTheirPath) {
  // 100 000 brackets overflowed the stack when a message quoted the value (nlohmann's dump).
  const std::string deep = "{\"mesh\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  std::string msg = refusal([&] { JsonDocument::parse(deep, "p.json"); });
  EXPECT_NE(msg.find("p.json: mesh[0][0]"), std::string::npos) << msg.substr(0, 200);
  EXPECT_NE(msg.find("nested deeper than 64 levels"), std::string::npos) << msg.substr(0, 200);
  // 63 levels inside the top object are still read.
  EXPECT_NO_THROW(JsonDocument::parse("{\"a\": " + std::string(63, '[') + std::string(63, ']') + "}", "p.json"));
  msg = refusal([] { JsonDocument::parse(R"({"solver": {"step": 1e-3, "end": 1}, "joints": [{"name": "a"}, {"name": "b", "name": "c"}]})", "m.json"); });
  EXPECT_NE(msg.find("m.json: joints[1].name: given twice in the same object"), std::string::npos) << msg;
  msg = refusal([] { JsonDocument::parse(R"({"solver": {"step": 1e-3}, "solver": {}})", "m.json"); });
  EXPECT_NE(msg.find("m.json: solver: given twice"), std::string::npos) << msg;
  // The same key in different objects is no repetition.
  EXPECT_NO_THROW(JsonDocument::parse(R"([{"name": "a"}, {"name": "b", "sub": {"name": "c"}}])", "m.json"));
}

TEST(JsonInput, HugeValuesAndIntegersBeyondLongLongAreRefused) {
  const auto doc = JsonDocument::parse(
      R"({"x": [0, 1e200, 0], "ok": -1e30, "dim": 1e19, "u": 18446744073709551615, "exact": 4e15, "neg": -7})", "f.json");
  const auto root = doc.root();
  std::string msg = refusal([&] { root.at("x").vec3(); });
  EXPECT_NE(msg.find("f.json: x[1]: magnitude beyond 1e30"), std::string::npos) << msg;
  EXPECT_EQ(root.at("ok").number(), -1e30);
  // 1e19 is integral but beyond long long: converting it was undefined (it gave 0).
  msg = refusal([&] { root.at("dim").integer(); });
  EXPECT_NE(msg.find("f.json: dim: integer out of range"), std::string::npos) << msg;
  msg = refusal([&] { root.at("u").integer(); });
  EXPECT_NE(msg.find("f.json: u: integer out of range"), std::string::npos) << msg;
  EXPECT_EQ(root.at("exact").integer(), 4000000000000000LL);
  EXPECT_EQ(root.at("neg").integer(), -7);
}

// Input that is not a regular file: a device never ends (ffr-sim on /dev/zero ran until it was
// killed, its memory growing), so it is refused naming the file; a pipe is read to its end, up
// to a bound (1 GiB by default; 10 bytes here).
TEST(JsonInput, DevicesAreRefusedAndPipesReadUpToABound) {
  EXPECT_NE(refusal([] { (void)JsonDocument::load("/dev/zero"); }).find("/dev/zero: is a device or socket, not a file"),
            std::string::npos);
  const auto dir = std::filesystem::temp_directory_path() / ("ffr_pipe_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto fifo = dir / "model.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string text = R"({"bodies": [], "solver": {"step": 0.001}})";
  const auto feed = [&] { std::ofstream(fifo) << text; };
  {
    std::thread writer(feed);
    const std::string read = ffr::formats::read_text_file(fifo);
    writer.join();
    EXPECT_EQ(read, text);
  }
  {
    std::thread writer(feed);
    const std::string what = refusal([&] { (void)ffr::formats::read_text_file(fifo, 10); });
    writer.join();
    EXPECT_NE(what.find("model.json: a pipe that gives more than 10 bytes; give the input as a file"), std::string::npos) << what;
  }
  std::filesystem::remove_all(dir);
}
