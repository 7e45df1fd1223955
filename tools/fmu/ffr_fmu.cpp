// ffr-fmu MODEL.json -o MODEL.fmu: the model as an FMI 2.0 Co-Simulation FMU.
#include "variables.hpp"
#include "zip_writer.hpp"

#include "ffr/cli/cli.hpp"
#include "ffr/cli/output_files.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/formats/sha256.hpp"
#include "ffr/runtime/runtime.hpp"
#include "ffr/version.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const ffr::cli::Command kCommand{
    "ffr-fmu",
    R"(
Packages the model MODEL.json as an FMI 2.0 Co-Simulation FMU for linux64: the runtime as
binaries/linux64/<id>.so (id: the model file's name), the model and its SID files under
resources/, and modelDescription.xml with
  outputs  every model output, "name" (one component) or "name[i]" (i from 0)
  inputs   "<joint>.value", ".rate", ".acceleration" for every motion (used instead of the
           table from the first time one is set); "<name>[i]" for every named point_force or
           point_torque at a node or a frame origin (added to its table, global components)
  parameter "solver.step" (fixed-step models): the integrator's step, settable until
           fmi2ExitInitializationMode (the model is then run with that step, as ffr-sim runs
           the model file with it)
The communication step must be a whole number of the model's steps (solver.step). The FMU
supports fmi2GetFMUstate / fmi2SetFMUstate and their serialization. It needs the HDF5 library
of the machine that runs it (Debian: libhdf5-103).

  -o, --output FILE   the FMU to write (required; written whole or not at all)
  -h, --help, --version

Exit status: 0 ok, 2 bad input (the model or a SID file it names), 1 other failure.
)",
    "ffr-fmu MODEL.json -o MODEL.fmu"};

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  if (!f) throw std::runtime_error("cannot read " + p.string());
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string xml(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The model identifier (a C name: the binary's file name): the model file's stem.
std::string identifier(const fs::path& model) {
  std::string id;
  for (char c : model.stem().string()) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "m_" + id;
  return id;
}

// The FMU's shared object: libexec/ffr/ beside the program's bin/ (build tree and installed).
fs::path binary_path() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path p = exe.parent_path().parent_path() / "libexec" / "ffr" / "ffr-fmi2.so";
  if (ec || !fs::exists(p, ec))
    throw std::runtime_error("the FMU's shared object " + p.string() + " was not found: the installation is incomplete");
  return p;
}

std::string model_description(const ffr::runtime::Model& model, const std::string& id, const std::string& guid,
                              const std::string& description) {
  const auto vars = ffr::fmu::variables(model);
  const auto& s = model.settings;
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" + xml(id) + "\" guid=\"" + guid +
       "\" description=\"" + xml(description) + "\" generationTool=\"ffr-fmu " + ffr::kVersion +
       "\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">\n";
  x += "  <CoSimulation modelIdentifier=\"" + id +
       "\" canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\""
       " maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\""
       " canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\""
       " providesDirectionalDerivative=\"false\"/>\n";
  x += "  <DefaultExperiment startTime=\"" + number(s.start) + "\" stopTime=\"" + number(s.end) + "\" stepSize=\"" +
       number(s.adaptive ? s.output_interval : s.step) + "\"/>\n";
  x += "  <ModelVariables>\n";
  std::vector<std::size_t> outputs;
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const auto& v = vars[i];
    const bool out = v.kind == ffr::fmu::Variable::Kind::Output;
    const bool parameter = v.kind == ffr::fmu::Variable::Kind::Parameter;
    x += "    <ScalarVariable name=\"" + xml(v.name) + "\" valueReference=\"" + std::to_string(i) +
         "\" description=\"" + xml(v.description) + "\" causality=\"" +
         (out ? "output" : parameter ? "parameter" : "input") + "\" variability=\"" +
         (parameter ? "fixed\" initial=\"exact" : "continuous") + "\">" +
         (out ? std::string("<Real/>")
              : parameter ? "<Real start=\"" + number(s.step) + "\" min=\"0\"/>" : std::string("<Real start=\"0\"/>")) +
         "</ScalarVariable>\n";
    if (out) outputs.push_back(i + 1);
  }
  x += "  </ModelVariables>\n  <ModelStructure>\n";
  for (const char* list : {"Outputs", "InitialUnknowns"}) {
    x += std::string("    <") + list + ">\n";
    for (auto k : outputs) x += "      <Unknown index=\"" + std::to_string(k) + "\"/>\n";
    x += std::string("    </") + list + ">\n";
  }
  x += "  </ModelStructure>\n</fmiModelDescription>\n";
  return x;
}

int run(ffr::cli::Args& args) {
  auto out = args.option("-o");
  if (auto o = args.option("--output")) out = o;
  const auto pos = args.positionals();
  if (pos.size() != 1) throw ffr::cli::UsageError("expected one model file");
  if (!out) throw ffr::cli::UsageError("no FMU file given (-o MODEL.fmu)");
  const fs::path model_file = pos[0];

  // The whole model as ffr-sim reads it: every error of the model or of a SID file now.
  ffr::runtime::Model model;
  try {
    model = ffr::runtime::load_model(model_file);
  } catch (const ffr::runtime::ModelError& e) {
    std::fprintf(stderr, "ffr-fmu: error: %s\n", e.what());
    return 2;
  }
  std::vector<ffr::cli::NamedPath> inputs{{"the model file", model_file}};
  for (const auto& sid : model.sid_files) inputs.push_back({"the SID file", sid});
  ffr::cli::check_outputs({{"-o", *out}}, inputs);

  // Variable names must be unique in modelDescription.xml: an output "a[0]" beside a vector
  // output "a", or an output named like an input, cannot be packaged.
  {
    std::set<std::string> names;
    for (const auto& v : ffr::fmu::variables(model))
      if (!names.insert(v.name).second) {
        std::fprintf(stderr, "ffr-fmu: error: %s: outputs, motions and loads give the FMU variable '%s' twice; rename one\n",
                     model_file.c_str(), v.name.c_str());
        return 2;
      }
  }

  // The model file with its SID paths replaced by the copies' names under resources/.
  auto json = nlohmann::json::parse(read_file(model_file));
  std::vector<std::pair<std::string, std::string>> resources;  // name under resources/, bytes
  if (json.contains("bodies"))
    for (std::size_t b = 0; b < json["bodies"].size(); ++b) {
      auto& body = json["bodies"][b];
      if (!body.is_object() || !body.contains("sid")) continue;
      const fs::path sid = model_file.parent_path() / body["sid"].get<std::string>();
      const std::string name = "sid_" + std::to_string(b) + "_" + sid.filename().string();
      resources.emplace_back(name, read_file(sid));
      body["sid"] = name;
    }
  const std::string model_text = json.dump(1);
  resources.insert(resources.begin(), {"model.json", model_text});

  ffr::formats::Sha256 hash;
  for (const auto& [name, bytes] : resources) {
    hash.update(name.data(), name.size());
    hash.update(bytes.data(), bytes.size());
  }
  const std::string h = hash.hex();
  const std::string guid = "{" + h.substr(0, 8) + "-" + h.substr(8, 4) + "-" + h.substr(12, 4) + "-" +
                           h.substr(16, 4) + "-" + h.substr(20, 12) + "}";
  resources.emplace_back("ffr_guid.txt", guid + "\n");

  const std::string id = identifier(model_file);
  const std::string description = json.contains("description") && json["description"].is_string()
                                      ? json["description"].get<std::string>()
                                      : "ffr model " + model_file.filename().string();
  const std::string binary = read_file(binary_path());

  ffr::formats::h5::AtomicFile file(*out);
  {
    std::ofstream f(file.temp_path(), std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + file.temp_path().string());
    ffr::fmu::ZipWriter zip(f);
    zip.add("modelDescription.xml", model_description(model, id, guid, description));
    zip.add("binaries/linux64/" + id + ".so", binary);
    for (const auto& [name, bytes] : resources) zip.add("resources/" + name, bytes);
    zip.finish();
  }
  file.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return ffr::cli::run_main(argc, argv, kCommand, run); }
