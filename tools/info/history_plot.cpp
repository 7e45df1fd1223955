// ffr-info RESULTS.h5 --plot CH1,CH2[i],... --png OUT.png: time histories of output channels of
// an ffr-sim results file, one panel per channel (all its components, or the one selected).
#include "summary.hpp"

#include "ffr/cli/cli.hpp"
#include "ffr/cli/output_files.hpp"
#include "plot_axes.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>

namespace ffr::info {
namespace {

struct Selection {
  const formats::Results::Output* output;
  std::vector<Eigen::Index> columns;
};

// "name" (every component) or "name[i]" (0-based component i). A channel whose whole name is
// the spec is taken first: names such as "x[mm]" are allowed in a model file.
Selection select(const formats::Results& r, const std::string& spec, const std::string& file) {
  std::string name = spec;
  long column = -1;
  const bool whole = r.find(spec) != nullptr;
  if (const auto open = spec.rfind('['); !whole && open != std::string::npos) {
    const auto close = spec.find(']', open);
    char* end = nullptr;
    const std::string idx = spec.substr(open + 1, close == std::string::npos ? std::string::npos : close - open - 1);
    column = std::strtol(idx.c_str(), &end, 10);
    if (close != spec.size() - 1 || idx.empty() || *end != '\0' || column < 0)
      throw cli::UsageError("--plot: '" + spec + "' is neither NAME nor NAME[i] with i >= 0");
    name = spec.substr(0, open);
  }
  const auto it = std::find_if(r.outputs.begin(), r.outputs.end(), [&](const auto& o) { return o.name == name; });
  if (it == r.outputs.end()) {
    std::string known;
    for (const auto& o : r.outputs) known += (known.empty() ? "" : ", ") + o.name;
    throw std::invalid_argument(file + ": no output channel '" + name + "' (the file has: " + known + ")");
  }
  Selection s{&*it, {}};
  if (column >= 0) {
    if (column >= it->values.cols())
      throw std::invalid_argument(file + ": output channel '" + name + "' has " + std::to_string(it->values.cols()) +
                                  " components, no [" + std::to_string(column) + "]");
    s.columns.push_back(column);
  } else {
    for (Eigen::Index c = 0; c < it->values.cols(); ++c) s.columns.push_back(c);
  }
  return s;
}

// Whether select() finds a channel for the spec: a whole name, or a name followed by [i].
bool names_a_channel(const formats::Results& r, const std::string& spec) {
  const auto open = spec.rfind('[');
  return r.find(spec) || (open != std::string::npos && spec.back() == ']' && r.find(spec.substr(0, open)));
}

void draw_panel(Canvas& cv, const formats::Results& r, const Selection& s, int top, int height) {
  const auto& v = s.output->values;
  double y0 = 0, y1 = 0;
  bool first = true;
  for (const Eigen::Index c : s.columns)
    for (Eigen::Index i = 0; i < v.rows(); ++i) {
      y0 = first ? v(i, c) : std::min(y0, v(i, c));
      y1 = first ? v(i, c) : std::max(y1, v(i, c));
      first = false;
    }
  const double pad = 0.05 * (y1 - y0);
  const double t0 = r.time.size() ? r.time[0] : 0, t1 = r.time.size() ? r.time[r.time.size() - 1] : 1;
  std::string title = s.output->name + (s.output->type.empty() ? "" : " (" + s.output->type + ")");
  if (r.stopped_at) {  // the samples of a run that did not reach its end (ffr-sim --keep-partial)
    char at[64];
    std::snprintf(at, sizeof at, " - the run stopped at t = %.6g s", *r.stopped_at);
    title += at;
  }
  const PlotArea a = draw_axes(cv, PlotArea{110, top + 60, cv.width() - 30, top + height - 50, t0, t1, y0 - pad, y1 + pad},
                               title, "time [s]", "");
  int legend_x = a.left + 10;
  for (std::size_t k = 0; k < s.columns.size(); ++k) {
    const Rgb col = series_colour(k);
    const Eigen::Index c = s.columns[k];
    for (Eigen::Index i = 1; i < v.rows(); ++i)
      cv.line(a.X(r.time[i - 1]), a.Y(v(i - 1, c)), a.X(r.time[i]), a.Y(v(i, c)), col, 2);
    if (s.columns.size() > 1 || v.cols() > 1) {
      const std::string key = component_name(s.output->type, c, v.cols());
      cv.fill_rect(legend_x, a.top - 14, legend_x + 16, a.top - 10, col);
      cv.text(legend_x + 20, a.top - 19, key, col);
      legend_x += 20 + Canvas::text_width(key) + 16;
    }
  }
}

}  // namespace

int run_plot(const std::filesystem::path& file, const std::string& channels, const std::string& png) {
  if (png.empty()) throw cli::UsageError("--plot needs --png OUT.png");
  cli::check_outputs({{"--png", png}}, {{"the results file", file}});
  const formats::Results r = formats::read_results(file);
  std::vector<Selection> panels;
  std::size_t start = 0;
  while (start <= channels.size()) {
    // The longest run of comma-separated pieces that names a channel (an output name may hold
    // a comma), else the next piece alone, which select() then refuses with its message.
    std::vector<std::size_t> ends;
    for (auto c = channels.find(',', start); c != std::string::npos; c = channels.find(',', c + 1)) ends.push_back(c);
    ends.push_back(channels.size());
    std::size_t end = ends.front();
    for (auto e = ends.rbegin(); e != ends.rend(); ++e)
      if (names_a_channel(r, channels.substr(start, *e - start))) {
        end = *e;
        break;
      }
    const std::string spec = channels.substr(start, end - start);
    if (spec.empty()) throw cli::UsageError("--plot: empty channel name in '" + channels + "'");
    panels.push_back(select(r, spec, file.string()));
    if (end == channels.size()) break;
    start = end + 1;
  }
  const int panel_height = 360;
  Canvas cv(900, panel_height * static_cast<int>(panels.size()));
  for (std::size_t p = 0; p < panels.size(); ++p) try {
      draw_panel(cv, r, panels[p], static_cast<int>(p) * panel_height, panel_height);
    } catch (const std::invalid_argument& e) {  // values spanning more than a double holds
      throw std::invalid_argument(file.string() + ": output channel '" + panels[p].output->name + "': " + e.what());
    }
  write_png(cv, png);
  std::cout << "plot of " << channels << " written to " << png << "\n";
  if (r.stopped_at)
    std::cout << "note: " << file.string() << " holds a run that stopped at t = " << *r.stopped_at
              << " s, before its end: " << r.stop_reason << "\n";
  return 0;
}

}  // namespace ffr::info
