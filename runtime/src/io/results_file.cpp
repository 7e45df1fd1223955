// Results file writers: HDF5 through the project's strict layer, CSV as plain text; both are
// written to a temporary name and renamed when complete, so nothing half-written is left.
#include "ffr/formats/h5.hpp"
#include "ffr/runtime/outputs.hpp"
#include "ffr/version.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace ffr::runtime {

void write_results_h5(const std::filesystem::path& path, const Model& model, const Recorder& rec, const RunInfo& info) {
  namespace h5 = ffr::formats::h5;
  h5::AtomicFile out(path);
  {
    h5::Writer w(out.temp_path(), path.string());
    const auto nt = static_cast<std::uint64_t>(rec.rows());
    w.attr("/", "format", std::string("ffr-results"));
    w.attr("/", "format_version", std::int64_t{1});
    w.attr("/", "generator", std::string(ffr::kGenerator));
    w.attr("/", "model", model.source);
    w.attr("/", "steps", static_cast<std::int64_t>(info.steps));
    w.attr("/", "newton_iterations", static_cast<std::int64_t>(info.newton_iterations));
    w.attr("/", "integration_seconds", info.integration_seconds);
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
    }
    w.close();
  }
  out.commit();
}

void write_results_csv(const std::filesystem::path& path, const Model& model, const Recorder& rec) {
  ffr::formats::h5::AtomicFile out(path);
  {
    std::ofstream f(out.temp_path());
    if (!f) throw std::runtime_error(path.string() + ": cannot create the CSV file");
    f << "time";
    for (const Output& o : model.outputs)
      for (int k = 0; k < o.size; ++k) f << ',' << o.name << '[' << k << ']';
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
  out.commit();
}

}  // namespace ffr::runtime
