#include "optimize/map/map_output.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "io/build_info.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::optimize::map {

using nlohmann::json;

namespace {

std::string model_name(scene::ModelKind m) { return std::string(scene::to_string(m)); }

// Header cells of the axis columns.
std::string axis_header(const MapStudy& st) {
  std::string h = st.axes[0].name;
  h += "," + (st.axes.size() > 1 ? st.axes[1].name : std::string("row_value"));
  return h;
}

std::string axis_label(const MapAxis& a) {
  const std::string u = a.unit();
  return a.name + (u.empty() || u == "-" ? "" : " [" + u + "]");
}

std::string gp_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Cell edges along an axis: midpoints between neighbours (geometric on log
// axes), the ends mirrored; a single value gets +-5 % (or +-0.5).
std::vector<double> edges(const MapAxis& a) {
  const auto& v = a.values;
  const size_t n = v.size();
  std::vector<double> e(n + 1);
  if (n == 1) {
    const double h = v[0] != 0.0 ? 0.05 * std::abs(v[0]) : 0.5;
    e[0] = a.log_scale ? v[0] / 1.05 : v[0] - h;
    e[1] = a.log_scale ? v[0] * 1.05 : v[0] + h;
    return e;
  }
  for (size_t i = 1; i < n; ++i)
    e[i] = a.log_scale ? std::sqrt(v[i - 1] * v[i]) : 0.5 * (v[i - 1] + v[i]);
  e[0] = a.log_scale ? v[0] * v[0] / e[1] : 2.0 * v[0] - e[1];
  e[n] = a.log_scale ? v[n - 1] * v[n - 1] / e[n - 1] : 2.0 * v[n - 1] - e[n - 1];
  return e;
}

}  // namespace

std::string format_number(double v) {
  if (!std::isfinite(v)) v = 0.0;  // never written: every number is finite by construction
  if (v == 0.0) return "0";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

long first_disagreement_column(const MapStudy& st, const std::vector<CellSummary>& cells,
                               long row) {
  for (long c = 0; c < st.columns(); ++c)
    if (cells[static_cast<size_t>(row * st.columns() + c)].disagreements > 0) return c;
  return -1;
}

std::string cells_csv(const MapStudy& st, const std::vector<CellSummary>& cells) {
  std::ostringstream o;
  o << "cell,row,column," << axis_header(st) << ",trials";
  for (auto m : st.models) o << ",stabilized_" << model_name(m);
  const std::string a = model_name(st.models.front()), b = model_name(st.models.back());
  o << ",disagreements," << a << "_only," << (st.models.size() > 1 ? b : std::string("none"))
    << "_only,mean_settle_strides,spectral_radius,peak_force_N,mean_duty,fell_fraction\n";
  for (const CellSummary& c : cells) {
    o << c.index << ',' << c.row << ',' << c.column << ',' << format_number(c.value0) << ','
      << format_number(c.value1) << ',' << st.trials.count;
    for (double f : c.fraction) o << ',' << format_number(f);
    o << ',' << c.disagreements << ',' << c.a_only << ',' << c.b_only << ','
      << format_number(c.mean_settle_strides) << ',' << format_number(c.spectral_radius) << ','
      << format_number(c.peak_force) << ',' << format_number(c.mean_duty) << ','
      << format_number(c.fell_fraction) << '\n';
  }
  return o.str();
}

std::string trials_csv(const MapStudy& st, const std::vector<CellResult>& cells) {
  std::ostringstream o;
  o << "cell,row,column," << axis_header(st)
    << ",trial,seed_key,offset_x,offset_y,kick_x,kick_y,tilt_roll_deg,tilt_pitch_deg,"
       "tilt_yaw_deg,spin_x,spin_y,spin_z";
  for (auto m : st.models) {
    const std::string n = model_name(m);
    o << ',' << n << "_status," << n << "_stabilized," << n << "_settle_strides," << n
      << "_strides," << n << "_duty_mean," << n << "_peak_force_N";
  }
  o << '\n';
  constexpr double kToDeg = 180.0 / M_PI;
  for (const CellResult& c : cells) {
    const long row = cell_row(st, c.index), col = cell_column(st, c.index);
    const std::uint64_t key = cell_seed_key(st, c.index);
    const double v0 = st.axes[0].values[static_cast<size_t>(col)];
    const double v1 = st.axes.size() > 1 ? st.axes[1].values[static_cast<size_t>(row)] : 0.0;
    for (long t = 0; t < st.trials.count; ++t) {
      const Scenario s = trial_scenario(st, key, t);
      o << c.index << ',' << row << ',' << col << ',' << format_number(v0) << ','
        << format_number(v1) << ',' << t << ',' << key << ','
        << format_number(s.position_offset.x()) << ',' << format_number(s.position_offset.y())
        << ',' << format_number(s.velocity_kick.x()) << ',' << format_number(s.velocity_kick.y())
        << ',' << format_number(s.tilt.x() * kToDeg) << ',' << format_number(s.tilt.y() * kToDeg)
        << ',' << format_number(s.tilt.z() * kToDeg) << ',' << format_number(s.angular_velocity.x())
        << ',' << format_number(s.angular_velocity.y()) << ','
        << format_number(s.angular_velocity.z());
      for (const auto& per_model : c.trials) {
        const TrialOutcome& r = per_model[static_cast<size_t>(t)];
        o << ',' << r.status << ',' << (r.stabilized ? 1 : 0) << ',' << r.settle_strides << ','
          << r.strides << ',' << format_number(r.duty_mean) << ',' << format_number(r.peak_force);
      }
      o << '\n';
    }
  }
  return o.str();
}

std::string boundary_csv(const MapStudy& st, const std::vector<CellSummary>& cells,
                         const std::vector<BoundaryResult>& boundaries) {
  std::ostringstream o;
  o << "row," << (st.axes.size() > 1 ? st.axes[1].name : std::string("row_value"))
    << ",status,boundary,good,bad,probes,resolution,first_good,first_disagreement\n";
  for (const BoundaryResult& b : boundaries) {
    const double v1 = st.axes.size() > 1 ? st.axes[1].values[static_cast<size_t>(b.row)] : 0.0;
    const long fd = first_disagreement_column(st, cells, b.row);
    o << b.row << ',' << format_number(v1) << ',' << b.status << ',' << format_number(b.boundary)
      << ',' << format_number(b.good) << ',' << format_number(b.bad) << ',' << b.probes << ','
      << format_number(st.resolution) << ','
      << (b.status == "none_good" ? std::string() : format_number(b.first_good)) << ','
      << (fd >= 0 ? format_number(st.axes[0].values[static_cast<size_t>(fd)]) : std::string())
      << '\n';
  }
  return o.str();
}

namespace {

/// The study's settings: name, models, axes, trials, the definition of stabilized.
json map_summary_settings(const MapStudy& st) {
  json j;
  j["type"] = "pronk_map";
  j["name"] = st.name;
  j["study_hash"] = st.hash;
  j["version"] = pronk::version();
  j["commit"] = pronk::git_commit();
  json models = json::array();
  for (auto m : st.models) models.push_back(model_name(m));
  j["models"] = models;
  j["primary_model"] = model_name(st.primary_model());
  json axes = json::array();
  for (const MapAxis& a : st.axes) {
    json ja = {{"name", a.name},
               {"kind", std::string(to_string(a.kind))},
               {"unit", a.unit()},
               {"scale", a.log_scale ? "log" : "linear"},
               {"values", a.values}};
    if (a.kind == AxisKind::kPointer) ja["pointer"] = a.pointer;
    axes.push_back(ja);
  }
  j["axes"] = axes;
  j["trials_per_cell"] = st.trials.count;
  j["seed"] = st.trials.seed;
  j["seeding"] = st.seeding == Seeding::kRow ? "row" : "cell";
  j["trial_duration_s"] = st.trial_set.duration;
  // How cells.csv's spectral_radius was obtained (the full model has no stride map to evaluate).
  j["spectral_radius_method"] =
      !st.stability ? "off"
      : scene::is_full_model(st.primary_model())
          ? "estimate: affine map fitted to the touchdowns of 4 perturbed runs of 6 s"
          : "stride map linearised by central differences";
  const auto& c = st.stabilized;
  j["stabilized"] = {
      {"definition",
       "no fall or divergence, and from stride k <= within_strides to the end of the run (at least "
       "hold_strides strides) every touchdown has |x - x_d| and |y - y_d| < position_error, "
       "|roll| and |pitch| < tilt_deg and every apex within apex_error of l + h"},
      {"position_error_m", c.settle.position_error},
      {"tilt_deg", c.settle.tilt * 180.0 / M_PI},
      {"apex_error_m", c.settle.apex_error},
      {"within_strides", c.within_strides},
      {"hold_strides", c.hold_strides}};
  return j;
}

json map_summary_totals(const MapStudy& st, const std::vector<CellSummary>& cells,
                        const std::vector<BoundaryResult>& boundaries) {
  long disagreements = 0, a_only = 0, b_only = 0;
  std::vector<double> frac(st.models.size(), 0.0);
  for (const CellSummary& s : cells) {
    disagreements += s.disagreements;
    a_only += s.a_only;
    b_only += s.b_only;
    for (size_t m = 0; m < frac.size(); ++m) frac[m] += s.fraction[m];
  }
  json fr = json::object();
  for (size_t m = 0; m < frac.size(); ++m)
    fr[model_name(st.models[m])] = frac[m] / static_cast<double>(cells.size());
  long probes = 0;
  for (const auto& b : boundaries) probes += b.probes;
  json totals = {
      {"cells", st.cells()},
      {"trials", st.cells() * st.trials.count},
      {"simulations", st.cells() * st.trials.count * static_cast<long>(st.models.size()) +
                          probes * st.trials.count},
      {"disagreements", disagreements},
      {model_name(st.models.front()) + "_only", a_only},
      {"stabilized_fraction", fr}};
  if (st.models.size() > 1) totals[model_name(st.models.back()) + "_only"] = b_only;
  return totals;
}

/// Disagreement threshold along axis 0 (over all rows): the largest value below which no
/// cell has a disagreement, and the first value with one.
json map_summary_disagreement(const MapStudy& st, const std::vector<CellSummary>& cells) {
  long first_col = -1;
  for (long col = 0; col < st.columns() && first_col < 0; ++col)
    for (long row = 0; row < st.rows(); ++row)
      if (cells[static_cast<size_t>(row * st.columns() + col)].disagreements > 0) first_col = col;
  json d;
  d["axis"] = st.axes[0].name;
  d["first_disagreement"] =
      first_col >= 0 ? json(st.axes[0].values[static_cast<size_t>(first_col)]) : json(nullptr);
  d["no_disagreement_up_to"] = first_col > 0
                                   ? json(st.axes[0].values[static_cast<size_t>(first_col - 1)])
                               : first_col < 0 ? json(st.axes[0].values.back())
                                               : json(nullptr);
  return d;
}

json map_summary_boundary(const MapStudy& st, const std::vector<CellSummary>& cells,
                          const std::vector<BoundaryResult>& boundaries) {
  json bj = json::array();
  for (const BoundaryResult& b : boundaries) {
    const long fd = first_disagreement_column(st, cells, b.row);
    json one = {{"row", b.row},   {"status", b.status}, {"boundary", b.boundary},
                {"good", b.good}, {"bad", b.bad},       {"probes", b.probes}};
    if (st.axes.size() > 1) one[st.axes[1].name] = st.axes[1].values[static_cast<size_t>(b.row)];
    one["first_good"] = b.status == "none_good" ? json(nullptr) : json(b.first_good);
    one["first_disagreement"] =
        fd >= 0 ? json(st.axes[0].values[static_cast<size_t>(fd)]) : json(nullptr);
    bj.push_back(one);
  }
  return {{"axis", st.axes[0].name},
          {"resolution", st.resolution},
          {"definition",
           "per row, the largest axis value at which every trial of the primary model "
           "stabilizes: the last cell with all trials stabilized, bisected towards the "
           "next cell to the resolution; first_good is the lowest such cell"},
          {"rows", bj}};
}

}  // namespace

json summary_json(const MapStudy& st, const std::vector<CellSummary>& cells,
                  const std::vector<BoundaryResult>& boundaries) {
  json j = map_summary_settings(st);
  j["totals"] = map_summary_totals(st, cells, boundaries);
  j["disagreement"] = map_summary_disagreement(st, cells);
  j["boundary"] = map_summary_boundary(st, cells, boundaries);
  j["files"] = {"cells.csv",        "trials.csv",      "boundary.csv",
                "summary.json",     "fraction.svg",    "fraction.gp",
                "disagreement.svg", "disagreement.gp", "journal.jsonl"};
  return j;
}

BoundaryBlock boundary_block(const MapStudy& st, const std::vector<BoundaryResult>& boundaries) {
  const bool two_d = st.axes.size() > 1;
  const MapAxis& ax = st.axes[0];
  BoundaryBlock out;
  std::ostringstream o;
  o << "# boundary, row value, lowest cell with all trials stabilized (rows with one; a blank\n"
       "# line at a row with none, where the line breaks)\n$boundary << EOD\n";
  bool broken = false;  // a blank line already ends the data written so far
  for (const BoundaryResult& b : boundaries) {
    if (b.status == "none_good") {
      if (out.any && !broken) o << '\n';
      broken = true;
      continue;
    }
    out.any = true;
    broken = false;
    out.band = out.band || b.first_good > ax.values.front();
    const std::string edges = format_number(b.boundary) + ' ';
    const std::string lower = ' ' + format_number(b.first_good) + '\n';
    if (two_d) {
      o << edges << format_number(st.axes[1].values[static_cast<size_t>(b.row)]) << lower;
    } else {
      o << edges << '0' << lower << edges << '1' << lower;
    }
  }
  o << "EOD\n";
  out.text = o.str();
  return out;
}

std::string heatmap_script(const MapStudy& st, const std::vector<CellSummary>& cells,
                           const std::vector<BoundaryResult>& boundaries, const std::string& what) {
  const bool two_d = st.axes.size() > 1;
  const MapAxis& ax = st.axes[0];
  const std::vector<double> ex = edges(ax);
  const std::vector<double> ey = two_d ? edges(st.axes[1]) : std::vector<double>{0.0, 1.0};
  const bool disagreement = what == "disagreement";
  const std::string primary = model_name(st.primary_model());
  std::ostringstream o;
  o << "# " << (disagreement ? "Disagreement" : "Fraction stabilized") << " map of " << st.name
    << " (written by pronk map; restyle and run: gnuplot " << what << ".gp)\n";
  o << "set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'\n";
  o << "set output '" << what << ".svg'\n";
  if (disagreement) {
    o << "set title "
      << gp_quote("Disagreement " + model_name(st.models.front()) + " vs " + primary +
                  ": fraction of " + run::count_text(st.trials.count, "trial") +
                  " stabilized by exactly one model")
      << " noenhanced\n";
    o << "set palette defined (0 '#ffffff', 0.25 '#fdd49e', 0.5 '#fc8d59', 1 '#b30000')\n";
  } else {
    o << "set title "
      << gp_quote("Fraction of " + run::count_text(st.trials.count, "trial") + " stabilized (" +
                  primary + " model)")
      << " noenhanced\n";
    o << "set palette defined (0 '#b2182b', 0.5 '#f7f7f7', 1 '#2166ac')\n";
  }
  o << "set cbrange [0:1]\nset xlabel " << gp_quote(axis_label(ax)) << " noenhanced\n";
  if (two_d)
    o << "set ylabel " << gp_quote(axis_label(st.axes[1])) << " noenhanced\n";
  else
    o << "unset ytics\n";
  if (ax.log_scale) o << "set logscale x\n";
  if (two_d && st.axes[1].log_scale) o << "set logscale y\n";
  o << "set xrange [" << format_number(ex.front()) << ":" << format_number(ex.back()) << "]\n";
  o << "set yrange [" << format_number(ey.front()) << ":" << format_number(ey.back()) << "]\n";
  o << "set key outside bottom center horizontal\n";
  o << "# x y x_lo x_hi y_lo y_hi value\n$cells << EOD\n";
  for (const CellSummary& c : cells) {
    const double y = two_d ? c.value1 : 0.5;
    const double v =
        disagreement ? static_cast<double>(c.disagreements) / static_cast<double>(st.trials.count)
                     : c.fraction.back();
    o << format_number(c.value0) << ' ' << format_number(y) << ' '
      << format_number(ex[static_cast<size_t>(c.column)]) << ' '
      << format_number(ex[static_cast<size_t>(c.column) + 1]) << ' '
      << format_number(ey[static_cast<size_t>(c.row)]) << ' '
      << format_number(ey[static_cast<size_t>(c.row) + 1]) << ' ' << format_number(v) << '\n';
  }
  o << "EOD\n";
  const BoundaryBlock bb = boundary_block(st, boundaries);
  o << bb.text;
  const bool any = bb.any, band = bb.band;
  o << "plot $cells using 1:2:3:4:5:6:7 with boxxyerror fill solid 1.0 noborder lc palette "
       "notitle";
  if (any)
    o << ", \\\n     $boundary using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc rgb 'black' title "
      << gp_quote("boundary: all " + primary + " trials stabilized") << " noenhanced";
  if (band)
    o << ", \\\n     $boundary using 3:2 with linespoints lw 2 dt 2 pt 6 ps 0.6 lc rgb 'black' "
         "title 'lowest cell with all trials stabilized' noenhanced";
  o << "\n";
  return o.str();
}

}  // namespace pronk::optimize::map
