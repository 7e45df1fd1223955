// Results file writers: HDF5 through the project's strict layer, CSV as plain text; both are
// written to temporary names and renamed only when both are complete, so a failure leaves
// neither file (nor half of one).
#include "ffr/formats/h5.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/runtime/outputs.hpp"
#include "ffr/version.hpp"

#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

namespace ffr::runtime {

namespace {

// The model file's name of an output type: written as the dataset's `type` attribute
// (formats/SPEC.md section 13), which ffr-info uses to name the components in its plots.
const char* output_type_name(OutputType t) {
  switch (t) {
    case OutputType::NodeDeformation: return "node_deformation";
    case OutputType::NodePosition: return "node_position";
    case OutputType::ModalCoordinates: return "modal_coordinates";
    case OutputType::JointCoordinate: return "joint_coordinate";
    case OutputType::Energy: return "energy";
    default: return nullptr;
  }
}

void write_h5(const std::filesystem::path& temp, const std::filesystem::path& path, const Model& model, const Recorder& rec,
              const RunInfo& info) {
  namespace h5 = ffr::formats::h5;
  {
    h5::Writer w(temp, path.string());
    const auto nt = static_cast<std::uint64_t>(rec.rows());
    w.attr("/", "format", std::string("ffr-results"));
    w.attr("/", "format_version", std::int64_t{ffr::formats::kResultsFormatVersion});
    w.attr("/", "generator", std::string(ffr::kGenerator));
    w.attr("/", "model", model.source);
    w.attr("/", "steps", static_cast<std::int64_t>(info.steps));
    w.attr("/", "newton_iterations", static_cast<std::int64_t>(info.newton_iterations));
    w.attr("/", "factorizations", static_cast<std::int64_t>(info.factorizations));
    w.attr("/", "solves", static_cast<std::int64_t>(info.solves));
    w.attr("/", "integration_seconds", info.integration_seconds);
    if (info.stopped_at) {  // a run that stopped before its end (ffr-sim --keep-partial)
      w.attr("/", "stopped_at", *info.stopped_at);
      w.attr("/", "stop_reason", info.stop_reason);
    }
    if (!info.restart.empty()) {  // the state it reached, to resume from (resume.cpp)
      w.write("/restart/state", info.restart.data(), {static_cast<std::uint64_t>(info.restart.size())});
      w.attr("/restart", "inputs_sha256", input_identity(model));
    }
    w.write("/time", rec.times().data(), {nt});
    w.ensure_group("/outputs");
    std::vector<double> buf;
    for (std::size_t i = 0; i < model.outputs.size(); ++i) {
      const MatrixXd& v = rec.values(i);
      const auto k = static_cast<std::uint64_t>(v.cols());
      buf.assign(nt * k, 0.0);
      for (std::uint64_t r = 0; r < nt; ++r)
        for (std::uint64_t c = 0; c < k; ++c) buf[r * k + c] = v(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
      w.write("/outputs/" + model.outputs[i].name, buf.data(), {nt, k});
      if (const char* type = output_type_name(model.outputs[i].type))
        w.attr("/outputs/" + model.outputs[i].name, "type", std::string(type));
    }
    w.close();
  }
}

// A header field as RFC 4180 has it: quoted, its quotes doubled, when it holds a comma, a quote or
// a line break. An output name may hold any of them, and written bare they would shift every
// later column under the wrong heading.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + '"';
}

void write_csv(const std::filesystem::path& temp, const std::filesystem::path& path, const Model& model, const Recorder& rec) {
  {
    std::ofstream f(temp);
    if (!f) throw std::runtime_error(path.string() + ": cannot create the CSV file");
    f << "time";
    for (const Output& o : model.outputs)
      for (int k = 0; k < o.size; ++k) f << ',' << csv_field(o.name + '[' + std::to_string(k) + ']');
    f << '\n';
    char buf[32];
    for (std::int64_t r = 0; r < rec.rows(); ++r) {
      std::snprintf(buf, sizeof buf, "%.17g", rec.times()(r));
      f << buf;
      for (std::size_t i = 0; i < model.outputs.size(); ++i)
        for (Eigen::Index k = 0; k < rec.values(i).cols(); ++k) {
          std::snprintf(buf, sizeof buf, "%.17g", rec.values(i)(r, k));
          f << ',' << buf;
        }
      f << '\n';
    }
    f.flush();
    if (!f) throw std::runtime_error(path.string() + ": writing the CSV file failed");
  }
}

}  // namespace

void write_results(const std::filesystem::path& h5_path, const std::optional<std::filesystem::path>& csv_path,
                   const Model& model, const Recorder& rec, const RunInfo& info) {
  ffr::formats::h5::AtomicFile h5_out(h5_path);
  write_h5(h5_out.temp_path(), h5_path, model, rec, info);
  std::optional<ffr::formats::h5::AtomicFile> csv_out;
  if (csv_path) {
    csv_out.emplace(*csv_path);
    write_csv(csv_out->temp_path(), *csv_path, model, rec);
  }
  h5_out.commit();
  if (csv_out) csv_out->commit();
}

}  // namespace ffr::runtime
