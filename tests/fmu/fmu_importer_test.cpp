// An FMU of ffr-fmu, used as an FMI 2.0 importer uses one: unpacked with Info-ZIP's unzip, its
// binaries/linux64/<id>.so loaded with dlopen, the value references read from
// modelDescription.xml, and only the standard's functions called (declared in tools/fmu/fmi2.h
// from the FMI 2.0 specification). Reference: ffr-sim's results of the same model file.
#include "fmi2.h"

#include "ffr/formats/results_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <dlfcn.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kBin = fs::path(FFR_BINARY_DIR) / "bin";
const fs::path kModels = fs::path(FFR_SOURCE_DIR) / "meshes" / "models";

struct Command {
  int status;
  std::string output;  // stdout and stderr
};

Command sh(const std::string& cmd) {
  Command c{-1, {}};
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return c;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) c.output += buf;
  const int s = pclose(p);
  c.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return c;
}

std::string q(const fs::path& p) {
  std::string s = "'";  // (built by appending: GCC 12's -Wrestrict misreads "'" + string)
  s += p.string();
  s += '\'';
  return s;
}

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<std::string> g_log;
void logger(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String format, ...) {
  char buf[2048];
  va_list ap;
  va_start(ap, format);
  std::vsnprintf(buf, sizeof buf, format, ap);
  va_end(ap);
  g_log.emplace_back(buf);
}

// The functions of one FMU's shared object, resolved by name as the standard names them.
struct Fmu {
  void* lib = nullptr;
  fmi2InstantiateTYPE* instantiate;
  fmi2FreeInstanceTYPE* free_instance;
  fmi2SetupExperimentTYPE* setup;
  fmi2EnterInitializationModeTYPE* enter_init;
  fmi2ExitInitializationModeTYPE* exit_init;
  fmi2DoStepTYPE* do_step;
  fmi2GetRealTYPE* get_real;
  fmi2SetRealTYPE* set_real;
  fmi2GetFMUstateTYPE* get_state;
  fmi2SetFMUstateTYPE* set_state;
  fmi2FreeFMUstateTYPE* free_state;
  fmi2SerializedFMUstateSizeTYPE* serialized_size;
  fmi2SerializeFMUstateTYPE* serialize;
  fmi2DeSerializeFMUstateTYPE* deserialize;
  fmi2TerminateTYPE* terminate;
  fmi2GetVersionTYPE* version;
  std::map<std::string, fmi2ValueReference> refs;
  std::map<std::string, std::string> causality;
  std::string guid, id;
  fs::path dir;

  template <class T>
  void sym(T*& f, const char* name) {
    f = reinterpret_cast<T*>(dlsym(lib, name));
    ASSERT_NE(f, nullptr) << name << ": " << dlerror();
  }

  void load(const fs::path& fmu, const fs::path& into) {
    dir = into;
    const auto u = sh("unzip -q -o " + q(fmu) + " -d " + q(into));
    ASSERT_EQ(u.status, 0) << u.output;
    const std::string md = read(into / "modelDescription.xml");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(md, m, std::regex("guid=\"([^\"]+)\"")));
    guid = m[1];
    ASSERT_TRUE(std::regex_search(md, m, std::regex("modelIdentifier=\"([^\"]+)\"")));
    id = m[1];
    const std::regex var("<ScalarVariable name=\"([^\"]+)\" valueReference=\"([0-9]+)\"[^>]*causality=\"([a-z]+)\"");
    for (auto it = std::sregex_iterator(md.begin(), md.end(), var); it != std::sregex_iterator(); ++it) {
      refs[(*it)[1]] = static_cast<fmi2ValueReference>(std::stoul((*it)[2]));
      causality[(*it)[1]] = (*it)[3];
    }
    const fs::path so = into / "binaries" / "linux64" / (id + ".so");
    lib = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(lib, nullptr) << dlerror();
    sym(instantiate, "fmi2Instantiate");
    sym(free_instance, "fmi2FreeInstance");
    sym(setup, "fmi2SetupExperiment");
    sym(enter_init, "fmi2EnterInitializationMode");
    sym(exit_init, "fmi2ExitInitializationMode");
    sym(do_step, "fmi2DoStep");
    sym(get_real, "fmi2GetReal");
    sym(set_real, "fmi2SetReal");
    sym(get_state, "fmi2GetFMUstate");
    sym(set_state, "fmi2SetFMUstate");
    sym(free_state, "fmi2FreeFMUstate");
    sym(serialized_size, "fmi2SerializedFMUstateSize");
    sym(serialize, "fmi2SerializeFMUstate");
    sym(deserialize, "fmi2DeSerializeFMUstate");
    sym(terminate, "fmi2Terminate");
    sym(version, "fmi2GetVersion");
  }

  // Instantiated and initialized; `parameters` are set in initialization mode (FMI 2.0 section 4.2.4).
  fmi2Component start(double t0, double t1, const std::map<std::string, double>& parameters = {}) {
    static const fmi2CallbackFunctions callbacks{logger, nullptr, nullptr, nullptr, nullptr};
    const std::string uri = "file://" + (dir / "resources").string();
    fmi2Component c = instantiate("importer", fmi2CoSimulation, guid.c_str(), uri.c_str(), &callbacks, fmi2False, fmi2False);
    if (!c) return nullptr;
    bool ok = setup(c, fmi2False, 0.0, t0, fmi2True, t1) == fmi2OK && enter_init(c) == fmi2OK;
    for (const auto& [name, value] : parameters) {
      const fmi2ValueReference vr = refs.at(name);
      ok = ok && set_real(c, &vr, 1, &value) == fmi2OK;
    }
    if (!ok || exit_init(c) != fmi2OK) {
      free_instance(c);
      return nullptr;
    }
    return c;
  }

  double get(fmi2Component c, const std::string& name) {
    const fmi2ValueReference vr = refs.at(name);
    double v = NAN;
    EXPECT_EQ(get_real(c, &vr, 1, &v), fmi2OK) << name;
    return v;
  }

  ~Fmu() {
    if (lib) dlclose(lib);
  }
};

class FmuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ffr_fmu_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    g_log.clear();
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// Four-bar (meshes/models/four_bar.json): 2 s in 1 ms communication steps, the crank angle of
// every step equal to ffr-sim's results (the same steps of the same integrator).
TEST_F(FmuTest, FourBarAgreesWithFfrSimAndRestoresState) {
  const fs::path model = kModels / "four_bar.json";
  const auto r = sh((kBin / "ffr-sim").string() + " " + q(model) + " -o " + q(dir_ / "ref.h5") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto ref = ffr::formats::read_results(dir_ / "ref.h5");
  const auto* angle = ref.find("crank_angle");
  ASSERT_NE(angle, nullptr);
  ASSERT_EQ(ref.time.size(), 2001);

  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(model) + " -o " + q(dir_ / "four_bar.fmu"));
  ASSERT_EQ(p.status, 0) << p.output;
  EXPECT_EQ(sh("unzip -tq " + q(dir_ / "four_bar.fmu")).status, 0);  // every entry's CRC
  Fmu fmu;
  fmu.load(dir_ / "four_bar.fmu", dir_ / "unpacked");
  ASSERT_NE(fmu.lib, nullptr);
  EXPECT_STREQ(fmu.version(), "2.0");
  EXPECT_EQ(fmu.causality.at("crank_angle"), "output");
  EXPECT_EQ(fmu.causality.at("energy[2]"), "output");  // a vector output's components
  fmi2Component c = fmu.start(0.0, 2.0);
  ASSERT_NE(c, nullptr) << (g_log.empty() ? "" : g_log.back());

  const double h = 1e-3;
  double worst = 0;
  std::vector<double> from_1s;
  fmi2FMUstate saved = nullptr;
  EXPECT_EQ(fmu.get(c, "crank_angle"), (*angle).values(0, 0));
  for (int k = 1; k <= 2000; ++k) {
    ASSERT_EQ(fmu.do_step(c, (k - 1) * h, h, fmi2False), fmi2OK) << k << ": " << (g_log.empty() ? "" : g_log.back());
    const double a = fmu.get(c, "crank_angle");
    worst = std::max(worst, std::abs(a - angle->values(k, 0)));
    if (k == 1000) {
      ASSERT_EQ(fmu.get_state(c, &saved), fmi2OK);
    }
    if (k > 1000) from_1s.push_back(a);
  }
  EXPECT_EQ(worst, 0.0) << "largest difference of the crank angle to ffr-sim's";
  EXPECT_GT(std::abs(angle->values(2000, 0) - angle->values(0, 0)), 1.0);  // the crank turned

  // Back to t = 1 s: the same continuation, bit for bit; also through the serialized state.
  ASSERT_EQ(fmu.set_state(c, saved), fmi2OK);
  for (int k = 1001; k <= 2000; ++k) {
    ASSERT_EQ(fmu.do_step(c, (k - 1) * h, h, fmi2False), fmi2OK);
    ASSERT_EQ(fmu.get(c, "crank_angle"), from_1s[k - 1001]) << k;
  }
  std::size_t n = 0;
  ASSERT_EQ(fmu.serialized_size(c, saved, &n), fmi2OK);
  std::vector<fmi2Byte> bytes(n);
  ASSERT_EQ(fmu.serialize(c, saved, bytes.data(), n), fmi2OK);
  fmi2FMUstate copy = nullptr;
  ASSERT_EQ(fmu.deserialize(c, bytes.data(), n, &copy), fmi2OK);
  ASSERT_EQ(fmu.set_state(c, copy), fmi2OK);
  ASSERT_EQ(fmu.do_step(c, 1.0, 0.5, fmi2False), fmi2OK);  // 500 model steps in one communication step
  EXPECT_EQ(fmu.get(c, "crank_angle"), from_1s[499]);
  EXPECT_EQ(fmu.get(c, "crank_angle"), angle->values(1500, 0));

  // Refused: a communication step that is no whole number of model steps, a wrong time, a
  // wrong state; each with a message to the logger and no change of the state.
  g_log.clear();
  EXPECT_EQ(fmu.do_step(c, 1.5, 1.5e-3 / 2, fmi2False), fmi2Error);
  ASSERT_FALSE(g_log.empty());
  EXPECT_NE(g_log.back().find("whole number"), std::string::npos) << g_log.back();
  EXPECT_EQ(fmu.do_step(c, 0.3, 1e-3, fmi2False), fmi2Error);
  EXPECT_EQ(fmu.deserialize(c, bytes.data(), n - 1, &copy), fmi2Error);
  const fmi2ValueReference out = fmu.refs.at("crank_angle");
  const double one = 1.0;
  EXPECT_EQ(fmu.set_real(c, &out, 1, &one), fmi2Error);  // an output
  EXPECT_EQ(fmu.get(c, "crank_angle"), angle->values(1500, 0));

  fmu.free_state(c, &saved);
  fmu.free_state(c, &copy);
  EXPECT_EQ(fmu.terminate(c), fmi2OK);
  EXPECT_EQ(fmu.do_step(c, 1.5, h, fmi2False), fmi2Error);  // terminated

  // fmi2Reset: the instance as after fmi2Instantiate; the run again gives ffr-sim's first steps.
  auto* reset = reinterpret_cast<fmi2ResetTYPE*>(dlsym(fmu.lib, "fmi2Reset"));
  ASSERT_NE(reset, nullptr);
  ASSERT_EQ(reset(c), fmi2OK);
  ASSERT_EQ(fmu.setup(c, fmi2False, 0.0, 0.0, fmi2True, 2.0), fmi2OK);
  ASSERT_EQ(fmu.enter_init(c), fmi2OK);
  ASSERT_EQ(fmu.exit_init(c), fmi2OK);
  for (int k = 1; k <= 3; ++k) {
    ASSERT_EQ(fmu.do_step(c, (k - 1) * h, h, fmi2False), fmi2OK);
    EXPECT_EQ(fmu.get(c, "crank_angle"), angle->values(k, 0)) << k;
  }
  fmu.free_instance(c);

  // A wrong GUID (another FMU's resources) is refused with a message.
  static const fmi2CallbackFunctions callbacks{logger, nullptr, nullptr, nullptr, nullptr};
  const std::string uri = "file://" + (fmu.dir / "resources").string();
  EXPECT_EQ(fmu.instantiate("x", fmi2CoSimulation, "{other}", uri.c_str(), &callbacks, 0, 0), nullptr);
}

// The parameter solver.step: set to 0.5 ms before initialization, the FMU's crank angle at every
// 1 ms communication point equals ffr-sim's on the four-bar model file holding "step": 0.0005
// (reference: ffr-sim's results of that file), and differs from the 1 ms run (the step changed).
TEST_F(FmuTest, StepParameterChangesTheStepAsInTheModelFile) {
  auto model = nlohmann::json::parse(read(kModels / "four_bar.json"));
  model["solver"]["end"] = 0.5;
  std::ofstream(dir_ / "four_bar.json") << model.dump();
  model["solver"]["step"] = 0.0005;
  std::ofstream(dir_ / "half.json") << model.dump();
  for (const char* m : {"four_bar", "half"}) {
    const auto r = sh((kBin / "ffr-sim").string() + " " + q(dir_ / (std::string(m) + ".json")) + " -o " +
                      q(dir_ / (std::string(m) + ".h5")) + " --quiet");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const auto ref = ffr::formats::read_results(dir_ / "half.h5");
  const auto coarse = ffr::formats::read_results(dir_ / "four_bar.h5");
  ASSERT_EQ(ref.time.size(), 1001);
  ASSERT_EQ(coarse.time.size(), 501);
  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "four_bar.json") + " -o " + q(dir_ / "fb.fmu"));
  ASSERT_EQ(p.status, 0) << p.output;
  Fmu fmu;
  fmu.load(dir_ / "fb.fmu", dir_ / "unpacked");
  ASSERT_NE(fmu.lib, nullptr);
  ASSERT_EQ(fmu.causality.at("solver.step"), "parameter");
  EXPECT_NE(read(dir_ / "unpacked" / "modelDescription.xml").find("variability=\"fixed\" initial=\"exact\"><Real start=\"0.001\""),
            std::string::npos);

  fmi2Component c = fmu.start(0.0, 0.5, {{"solver.step", 0.0005}});
  ASSERT_NE(c, nullptr) << (g_log.empty() ? "" : g_log.back());
  EXPECT_EQ(fmu.get(c, "solver.step"), 0.0005);
  const double h = 1e-3;
  double worst = 0, change = 0;
  for (int k = 1; k <= 500; ++k) {
    ASSERT_EQ(fmu.do_step(c, (k - 1) * h, h, fmi2False), fmi2OK) << k << ": " << (g_log.empty() ? "" : g_log.back());
    ASSERT_NEAR(ref.time(2 * k), k * h, 1e-12);
    const double a = fmu.get(c, "crank_angle");
    worst = std::max(worst, std::abs(a - ref.find("crank_angle")->values(2 * k, 0)));
    change = std::max(change, std::abs(a - coarse.find("crank_angle")->values(k, 0)));
  }
  EXPECT_EQ(worst, 0.0) << "largest difference of the crank angle to ffr-sim's with step 0.0005";
  EXPECT_GT(change, 1e-9) << "the parameter did not change the step";
  std::printf("solver.step = 0.5 ms: largest difference to ffr-sim with that step %.3g, to the 1 ms run %.3g\n", worst,
              change);
  // A fixed parameter: refused once initialized, the value unchanged.
  const fmi2ValueReference vr = fmu.refs.at("solver.step");
  const double other = 0.001;
  g_log.clear();
  EXPECT_EQ(fmu.set_real(c, &vr, 1, &other), fmi2Error);
  ASSERT_FALSE(g_log.empty());
  EXPECT_NE(g_log.back().find("before fmi2ExitInitializationMode"), std::string::npos) << g_log.back();
  EXPECT_EQ(fmu.get(c, "solver.step"), 0.0005);
  fmu.free_instance(c);

  // A step of which the communication step is no whole number: refused at fmi2DoStep.
  c = fmu.start(0.0, 0.5, {{"solver.step", 0.0004}});
  ASSERT_NE(c, nullptr) << (g_log.empty() ? "" : g_log.back());
  g_log.clear();
  EXPECT_EQ(fmu.do_step(c, 0.0, h, fmi2False), fmi2Error);
  ASSERT_FALSE(g_log.empty());
  EXPECT_NE(g_log.back().find("whole number"), std::string::npos) << g_log.back();
  EXPECT_EQ(fmu.do_step(c, 0.0, 0.002, fmi2False), fmi2OK);  // 5 steps of 0.4 ms
  fmu.free_instance(c);
  // Not a step: refused when set.
  EXPECT_EQ(fmu.start(0.0, 0.5, {{"solver.step", -1.0}}), nullptr);
  EXPECT_EQ(fmu.start(0.0, 0.5, {{"solver.step", 0.0}}), nullptr);
}

// A flexible body (the SID, written by ffr-synth, travels in resources/) and a named point
// torque as an input: the FMU with the torque set through fmi2SetReal equals ffr-sim run on the
// model with that torque in its table.
TEST_F(FmuTest, FlexiblePendulumWithLoadInput) {
  auto s = sh((kBin / "ffr-synth").string() + " --chain --clamped --points 11 --modes 8 --EI 20 --EA 1e4 --stiffening -o " +
              q(dir_ / "chain.sid.h5"));
  ASSERT_EQ(s.status, 0) << s.output;
  auto model = nlohmann::json::parse(read(kModels / "flexible_pendulum.json"));
  model["solver"]["end"] = 0.2;
  const double torque = 0.7;  // N m about the hinge axis (y)
  auto with_torque = [&](double t) {
    auto m = model;
    nlohmann::json table = nlohmann::json::object();
    table["t"] = {0.0, 1.0};
    table["value"] = nlohmann::json::array({nlohmann::json::array({0.0, t, 0.0}), nlohmann::json::array({0.0, t, 0.0})});
    nlohmann::json force = nlohmann::json::object();
    force["type"] = "point_torque";
    force["name"] = "drive";
    force["body"] = "hub";
    force["table"] = table;
    m["forces"] = nlohmann::json::array({force});
    return m.dump();
  };
  std::ofstream(dir_ / "ref.json") << with_torque(torque);
  std::ofstream(dir_ / "model.json") << with_torque(0.0);
  const auto r = sh((kBin / "ffr-sim").string() + " " + q(dir_ / "ref.json") + " -o " + q(dir_ / "ref.h5") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto ref = ffr::formats::read_results(dir_ / "ref.h5");
  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "model.json") + " -o " + q(dir_ / "pend.fmu"));
  ASSERT_EQ(p.status, 0) << p.output;
  fs::remove(dir_ / "chain.sid.h5");  // the FMU carries its own copy
  Fmu fmu;
  fmu.load(dir_ / "pend.fmu", dir_ / "unpacked");
  ASSERT_NE(fmu.lib, nullptr);
  ASSERT_EQ(fmu.causality.at("drive[1]"), "input");
  // As an importer sets inputs: in initialization mode, so they act from the start time.
  static const fmi2CallbackFunctions callbacks{logger, nullptr, nullptr, nullptr, nullptr};
  const std::string uri = "file://" + (fmu.dir / "resources").string();
  fmi2Component c = fmu.instantiate("importer", fmi2CoSimulation, fmu.guid.c_str(), uri.c_str(), &callbacks, 0, 0);
  ASSERT_NE(c, nullptr) << (g_log.empty() ? "" : g_log.back());
  ASSERT_EQ(fmu.setup(c, fmi2False, 0.0, ref.time[0], fmi2True, ref.time[ref.time.size() - 1]), fmi2OK);
  ASSERT_EQ(fmu.enter_init(c), fmi2OK);
  const fmi2ValueReference in = fmu.refs.at("drive[1]");
  ASSERT_EQ(fmu.set_real(c, &in, 1, &torque), fmi2OK);
  ASSERT_EQ(fmu.exit_init(c), fmi2OK) << (g_log.empty() ? "" : g_log.back());
  double worst = 0, scale = 0;
  for (Eigen::Index k = 1; k < ref.time.size(); ++k) {
    ASSERT_EQ(fmu.do_step(c, ref.time[k - 1], ref.time[k] - ref.time[k - 1], fmi2False), fmi2OK)
        << (g_log.empty() ? "" : g_log.back());
    for (const auto& o : ref.outputs)
      for (Eigen::Index j = 0; j < o.values.cols(); ++j) {
        const std::string name = o.values.cols() == 1 ? o.name : o.name + "[" + std::to_string(j) + "]";
        worst = std::max(worst, std::abs(fmu.get(c, name) - o.values(k, j)) / (1e-3 + std::abs(o.values(k, j))));
        scale = std::max(scale, std::abs(o.values(k, j)));
      }
  }
  // The torque enters the same generalized force once from the table, once as an external load:
  // equal to round-off.
  EXPECT_LT(worst, 1e-10) << "largest relative difference of any output to ffr-sim's";
  std::printf("flexible pendulum with a torque input: largest relative difference to ffr-sim %.3g\n", worst);
  const auto* angle = ref.find("angle");
  EXPECT_GT(std::abs(angle->values(ref.time.size() - 1, 0)), 1e-3);  // it moved
  fmu.free_instance(c);
}

// A motion as an input: the pendulum's hinge held by its table at 0 until the importer sets
// "hinge.value"; from then on the joint follows the input (reference: the value set).
TEST_F(FmuTest, MotionInputDrivesTheJoint) {
  auto model = nlohmann::json::parse(read(kModels / "pendulum.json"));
  model["solver"]["end"] = 0.1;
  nlohmann::json motion = nlohmann::json::object();
  motion["joint"] = "hinge";
  motion["table"] = nlohmann::json::object();
  motion["table"]["t"] = {0.0, 1.0};
  motion["table"]["value"] = {0.0, 0.0};
  model["motions"] = nlohmann::json::array({motion});
  std::ofstream(dir_ / "pendulum.json") << model.dump();
  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "pendulum.json") + " -o " + q(dir_ / "p.fmu"));
  ASSERT_EQ(p.status, 0) << p.output;
  Fmu fmu;
  fmu.load(dir_ / "p.fmu", dir_ / "unpacked");
  ASSERT_NE(fmu.lib, nullptr);
  ASSERT_EQ(fmu.causality.at("hinge.value"), "input");
  ASSERT_EQ(fmu.causality.at("hinge.rate"), "input");
  fmi2Component c = fmu.start(0.0, 0.1);
  ASSERT_NE(c, nullptr) << (g_log.empty() ? "" : g_log.back());
  const double h = 1e-3;
  for (int k = 0; k < 10; ++k) ASSERT_EQ(fmu.do_step(c, k * h, h, fmi2False), fmi2OK);
  EXPECT_NEAR(fmu.get(c, "angle"), 0.0, 1e-12);
  const fmi2ValueReference vr = fmu.refs.at("hinge.value");
  const double target = 1e-3;
  ASSERT_EQ(fmu.set_real(c, &vr, 1, &target), fmi2OK);
  for (int k = 10; k < 20; ++k) ASSERT_EQ(fmu.do_step(c, k * h, h, fmi2False), fmi2OK);
  EXPECT_NEAR(fmu.get(c, "angle"), target, 1e-12);
  const double nan = NAN;
  EXPECT_EQ(fmu.set_real(c, &vr, 1, &nan), fmi2Error);
  fmu.free_instance(c);
}

// Bad input: a model whose SID file is missing gives one message naming it, exit status 2 and
// no file (not even a partial one).
TEST_F(FmuTest, MissingSidIsRefusedWithoutOutput) {
  std::string text = read(kModels / "flexible_pendulum.json");
  std::ofstream(dir_ / "model.json") << text;  // chain.sid.h5 is not there
  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "model.json") + " -o " + q(dir_ / "pend.fmu"));
  EXPECT_EQ(p.status, 2) << p.output;
  EXPECT_NE(p.output.find("chain.sid.h5"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("ffr-fmu: error:"), std::string::npos) << p.output;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir_)) left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"model.json"});
  const auto u = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "model.json"));
  EXPECT_EQ(u.status, 2) << u.output;
}

// -o naming the model file replaced it by the FMU (exit 0): refused, the model untouched.
TEST_F(FmuTest, OutputNamingTheModelIsRefused) {
  const std::string text = read(kModels / "four_bar.json");
  std::ofstream(dir_ / "model.json") << text;
  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "model.json") + " -o " + q(dir_ / "." / "model.json"));
  EXPECT_EQ(p.status, 2) << p.output;
  EXPECT_NE(p.output.find("would overwrite the model file"), std::string::npos) << p.output;
  EXPECT_EQ(read(dir_ / "model.json"), text);
}

}  // namespace

namespace {

// Bad input: two variables of one name (a scalar output "energy[0]" beside the vector output
// "energy") are refused before anything is written.
TEST_F(FmuTest, DuplicateVariableNameIsRefused) {
  auto model = nlohmann::json::parse(read(kModels / "four_bar.json"));
  nlohmann::json out = nlohmann::json::object();
  out["name"] = "energy[0]";
  out["type"] = "joint_coordinate";
  out["joint"] = "O";
  model["outputs"].push_back(out);
  std::ofstream(dir_ / "model.json") << model.dump();
  const auto p = sh((kBin / "ffr-fmu").string() + " " + q(dir_ / "model.json") + " -o " + q(dir_ / "m.fmu"));
  EXPECT_EQ(p.status, 2) << p.output;
  EXPECT_NE(p.output.find("energy[0]"), std::string::npos) << p.output;
  EXPECT_FALSE(fs::exists(dir_ / "m.fmu"));
}

}  // namespace
