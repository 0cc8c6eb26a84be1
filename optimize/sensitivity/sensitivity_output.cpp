#include "optimize/sensitivity/sensitivity_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/load/input_error.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/figure_batch.hpp"
#include "io/write/table.hpp"

namespace pronk::optimize::sensitivity {

namespace {

using nlohmann::json;

json jnum(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string num(double v) { return std::isfinite(v) ? io::exact_number(v) : std::string(); }

std::string short_num(double v) {
  if (!std::isfinite(v)) return "–";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

json inputs_json(const DesignSensitivity& s) {
  json a = json::array();
  for (const auto& in : s.inputs) {
    a.push_back({{"name", in.name},
                 {"pointer", in.pointer},
                 {"tuned", in.tuned},
                 {"value", in.value},
                 {"range", in.range},
                 {"lower", in.lower},
                 {"upper", in.upper}});
  }
  return a;
}

json local_json(const DesignSensitivity& s) {
  json rows = json::array();
  const LocalResult& l = s.local;
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    for (size_t j = 0; j < s.inputs.size(); ++j) {
      rows.push_back({{"output", s.outputs[i]},
                      {"input", s.inputs[j].name},
                      {"derivative", jnum(l.derivative[i][j])},
                      {"error", jnum(l.error[i][j])},
                      {"elasticity", jnum(l.elasticity[i][j])},
                      {"at_lower", jnum(s.low[i][j])},
                      {"at_upper", jnum(s.high[i][j])}});
    }
  }
  json values = json::object();
  for (size_t i = 0; i < s.outputs.size(); ++i) values[s.outputs[i]] = jnum(l.f0[i]);
  return {{"step", s.local_step}, {"values", values}, {"derivatives", rows}};
}

json sobol_json(const DesignSensitivity& s) {
  if (!s.sobol) return nullptr;
  const SobolOptions& o = s.sobol_options;
  json rows = json::array(), var = json::object();
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    const SobolIndices& x = s.sobol->outputs[i];
    var[s.outputs[i]] = {{"mean", jnum(x.mean)}, {"variance", jnum(x.variance)}};
    for (size_t j = 0; j < s.inputs.size(); ++j) {
      rows.push_back({{"output", s.outputs[i]},
                      {"input", s.inputs[j].name},
                      {"S1", jnum(x.s1[j])},
                      {"S1_lo", jnum(x.s1_lo[j])},
                      {"S1_hi", jnum(x.s1_hi[j])},
                      {"ST", jnum(x.st[j])},
                      {"ST_lo", jnum(x.st_lo[j])},
                      {"ST_hi", jnum(x.st_hi[j])}});
    }
  }
  return {{"samples", o.samples},
          {"bootstrap", o.bootstrap},
          {"confidence", o.confidence},
          {"seed", o.seed},
          {"evaluations", s.sobol->evaluations},
          {"outputs", var},
          {"indices", rows}};
}

std::string local_csv(const DesignSensitivity& s) {
  std::string out = "output,input,derivative,error,elasticity\n";
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    for (size_t j = 0; j < s.inputs.size(); ++j) {
      out += s.outputs[i] + "," + s.inputs[j].name + "," + num(s.local.derivative[i][j]) + ",";
      out += num(s.local.error[i][j]);
      out += ",";
      out += num(s.local.elasticity[i][j]);
      out += "\n";
    }
  }
  return out;
}

std::string sobol_csv(const DesignSensitivity& s) {
  std::string out = "output,input,S1,S1_lo,S1_hi,ST,ST_lo,ST_hi\n";
  if (!s.sobol) return out;
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    const SobolIndices& x = s.sobol->outputs[i];
    for (size_t j = 0; j < s.inputs.size(); ++j) {
      out += s.outputs[i];
      out += ",";
      out += s.inputs[j].name;
      for (double v : {x.s1[j], x.s1_lo[j], x.s1_hi[j], x.st[j], x.st_lo[j], x.st_hi[j]}) {
        out += ",";
        out += num(v);
      }
      out += "\n";
    }
  }
  return out;
}

std::string tornado_csv(const DesignSensitivity& s) {
  std::string out = "output,input,value,lower,upper,f0,f_lower,f_upper\n";
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    for (size_t j = 0; j < s.inputs.size(); ++j) {
      const SensitivityInput& in = s.inputs[j];
      out += s.outputs[i];
      out += ",";
      out += in.name;
      for (double v : {in.value, in.lower, in.upper, s.local.f0[i], s.low[i][j], s.high[i][j]}) {
        out += ",";
        out += num(v);
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace

namespace {

// Inputs of output i, by the span of their one-at-a-time ends (largest first).
std::vector<size_t> by_span(const DesignSensitivity& s, size_t i) {
  std::vector<size_t> order(s.inputs.size());
  std::iota(order.begin(), order.end(), 0);
  auto span = [&](size_t j) {
    const double a = std::abs(s.high[i][j] - s.local.f0[i]),
                 b = std::abs(s.low[i][j] - s.local.f0[i]);
    const double m = std::max(std::isfinite(a) ? a : 0.0, std::isfinite(b) ? b : 0.0);
    return m;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return span(a) > span(b); });
  return order;
}

// Tornado: bars from the design's value to the output with the input at each end of its
// range, the largest at the top.
void tornado_figure(const DesignSensitivity& s, const std::string& dir, size_t i,
                    io::FigureBatch& figures) {
  const std::vector<size_t> order = by_span(s, i);
  std::string data = "# input y f0 f_lower f_upper\n";
  const size_t n = order.size();
  for (size_t r = 0; r < n; ++r) {
    const size_t j = order[r];
    data += "\"" + s.inputs[j].name + "\" " + std::to_string(n - 1 - r) + " " + num(s.local.f0[i]) +
            " ";
    data += num(s.low[i][j]).empty() ? "NaN" : num(s.low[i][j]);
    data += " ";
    data += num(s.high[i][j]).empty() ? "NaN" : num(s.high[i][j]);
    data += "\n";
  }
  io::write_file_atomic(dir + "/tornado.dat", data);
  std::ostringstream gp;
  gp << "set terminal svg size 900," << 160 + 28 * n << " dynamic enhanced font 'Helvetica,11'\n"
     << "set output 'tornado.svg'\n"
     << "set title noenhanced \"" << s.outputs[i] << " of " << s.study
     << ": each input at the ends of its range, the others at the design\"\n"
     << "set xlabel noenhanced '" << s.outputs[i] << "'\n"
     << "set ytics noenhanced\nset yrange [-0.7:" << n - 0.3 << "]\n"
     << "set style fill solid 0.7 border -1\nset grid xtics\nset key below "
        "horizontal\n"
     << "set arrow from " << num(s.local.f0[i]) << ", graph 0 to " << num(s.local.f0[i])
     << ", graph 1 nohead dt 2\n"
     << "plot 'tornado.dat' using (($3+$4)/2):2:($3<$4?$3:$4):($3<$4?$4:$3):($2-0.38):($2):"
        "ytic(1) with boxxyerror lc rgb '#4477aa' title 'input at its lower end', \\\n"
     << "     '' using (($3+$5)/2):2:($3<$5?$3:$5):($3<$5?$5:$3):($2):($2+0.38) with boxxyerror "
        "lc rgb '#cc6677' title 'input at its upper end'\n";
  figures.add(dir, "tornado", gp.str());
}

// Sobol bars: first-order and total indices of output i with their intervals.
void sobol_figure(const DesignSensitivity& s, const std::string& dir, size_t i,
                  io::FigureBatch& figures) {
  const SobolIndices& x = s.sobol->outputs[i];
  const size_t n = s.inputs.size();
  std::string data = "# input x S1 S1_lo S1_hi ST ST_lo ST_hi\n";
  auto v = [](double d) { return std::isfinite(d) ? num(d) : std::string("NaN"); };
  for (size_t j = 0; j < n; ++j) {
    data += "\"" + s.inputs[j].name + "\" " + std::to_string(j);
    for (double d : {x.s1[j], x.s1_lo[j], x.s1_hi[j], x.st[j], x.st_lo[j], x.st_hi[j]}) {
      data += " ";
      data += v(d);
    }
    data += "\n";
  }
  io::write_file_atomic(dir + "/sobol.dat", data);
  std::ostringstream gp;
  gp << "set terminal svg size 900,520 dynamic enhanced font 'Helvetica,11'\n"
     << "set output 'sobol.svg'\n"
     << "set title noenhanced \"Sobol indices of " << s.outputs[i] << " (" << s.study
     << ", N = " << s.sobol_options.samples << ", " << s.sobol_options.confidence * 100
     << " % bootstrap intervals)\"\n"
     << "set ylabel 'index'\nset offsets 0, 0, graph 0.08, graph 0.02\nset xrange [-0.7:" << n - 0.3
     << "]\n"
     << "set xtics noenhanced rotate by -35\nset grid ytics\nset key top right\n"
     << "set style fill solid 0.7 border -1\n"
     << "plot 'sobol.dat' using ($2-0.19):3:($2-0.36):($2-0.02):(0):3:xtic(1) with boxxyerror "
        "lc rgb '#4477aa' title 'first order S1', \\\n"
     << "     '' using ($2+0.19):6:($2+0.02):($2+0.36):(0):6 with boxxyerror lc rgb '#cc6677' "
        "title 'total ST', \\\n"
     << "     '' using ($2-0.19):3:4:5 with yerrorbars lc rgb 'black' pt 0 notitle, \\\n"
     << "     '' using ($2+0.19):6:7:8 with yerrorbars lc rgb 'black' pt 0 notitle\n";
  figures.add(dir, "sobol", gp.str());
}

std::string summary_md(const DesignSensitivity& s, size_t c) {
  std::ostringstream md;
  md << "# Sensitivity of " << s.study << "\n\nDesign `" << s.design_path << "`, " << s.model
     << " model, the study's " << s.set << " (" << s.scenarios << " trials, the same in every "
     << "evaluation). Physical numbers change "
     << (s.plant ? "the robot only (the controller keeps the design's numbers)"
                 : "robot and controller alike (the design with that number)")
     << ". " << s.evaluations << " evaluations (local " << short_num(s.local_seconds)
     << " s, Sobol " << short_num(s.sobol_seconds) << " s)";
  if (s.failed > 0) md << "; " << s.failed << " made no valid scene (their outputs are empty)";
  md << ".\n\n## " << s.outputs[c] << " = " << short_num(s.local.f0[c])
     << "\n\n| input | value | range | d/dx | ± | elasticity | at lower | at upper |"
     << (s.sobol ? " S1 [CI] | ST [CI] |" : "") << "\n|---|---|---|---|---|---|---|---|"
     << (s.sobol ? "---|---|" : "") << "\n";
  for (size_t j : by_span(s, c)) {
    const SensitivityInput& in = s.inputs[j];
    md << "| " << in.name << (in.tuned ? "" : " (physical)") << " | " << short_num(in.value)
       << " | ±" << short_num(100 * in.range) << " % | " << short_num(s.local.derivative[c][j])
       << " | " << short_num(s.local.error[c][j]) << " | " << short_num(s.local.elasticity[c][j])
       << " | " << short_num(s.low[c][j]) << " | " << short_num(s.high[c][j]) << " |";
    if (s.sobol) {
      const SobolIndices& x = s.sobol->outputs[c];
      md << " " << short_num(x.s1[j]) << " [" << short_num(x.s1_lo[j]) << ", "
         << short_num(x.s1_hi[j]) << "] | " << short_num(x.st[j]) << " [" << short_num(x.st_lo[j])
         << ", " << short_num(x.st_hi[j]) << "] |";
    }
    md << "\n";
  }
  md << "\n## Every output's strongest input\n\n| output | value | largest \\|elasticity\\| "
     << "| largest swing over the ranges |" << (s.sobol ? " largest ST |" : "")
     << "\n|---|---|---|---|" << (s.sobol ? "---|" : "") << "\n";
  for (size_t i = 0; i < s.outputs.size(); ++i) {
    size_t e = 0;
    for (size_t j = 1; j < s.inputs.size(); ++j) {
      const double a = std::abs(s.local.elasticity[i][j]), b = std::abs(s.local.elasticity[i][e]);
      if (std::isfinite(a) && (!std::isfinite(b) || a > b)) e = j;
    }
    const size_t w = by_span(s, i).front();
    md << "| " << s.outputs[i] << " | " << short_num(s.local.f0[i]) << " | " << s.inputs[e].name
       << " (" << short_num(s.local.elasticity[i][e]) << ") | " << s.inputs[w].name << " ("
       << short_num(s.low[i][w]) << " .. " << short_num(s.high[i][w]) << ") |";
    if (s.sobol) {
      const SobolIndices& x = s.sobol->outputs[i];
      size_t t = 0;
      for (size_t j = 1; j < s.inputs.size(); ++j)
        if (std::isfinite(x.st[j]) && (!std::isfinite(x.st[t]) || x.st[j] > x.st[t])) t = j;
      md << " "
         << (std::isfinite(x.st[t]) ? s.inputs[t].name + " (" + short_num(x.st[t]) + ")"
                                    : std::string("does not vary"))
         << " |";
    }
    md << "\n";
  }
  md << "\nFull tables: local.csv, sobol.csv, tornado.csv; everything: sensitivity.json. How to "
        "read them: docs/sensitivity.md.\n";
  return md.str();
}

}  // namespace

namespace {

std::string html_escape(const std::string& t) {
  std::string out;
  for (char ch : t) {
    if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else if (ch == '&')
      out += "&amp;";
    else if (ch == '`')
      continue;
    else
      out += ch;
  }
  return out;
}

// The cells of a markdown table row ("| a | b |"; "\\|" is a literal bar).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cur += '|';
      ++i;
    } else if (line[i] == '|') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += line[i];
    }
  }
  return out;
}

// report.html: summary.md's headings, paragraphs and tables as HTML, with the two figures
// (inlined, when gnuplot drew them) after the first table. No script: a static page.
std::string report_html(const std::string& md, const std::string& dir, const std::string& title) {
  std::string figures;
  for (const char* f : {"/tornado.svg", "/sobol.svg"}) {
    std::ifstream in(dir + f);
    if (!in) continue;
    std::stringstream svg;
    svg << in.rdbuf();
    const std::string text = svg.str();
    const size_t start = text.find("<svg");
    if (start != std::string::npos) figures += "<figure>" + text.substr(start) + "</figure>\n";
  }
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html_escape(title)
    << "</title>\n<style>body{font-family:Helvetica,Arial,sans-serif;max-width:1000px;margin:"
       "2em auto;padding:0 1em}table{border-collapse:collapse;display:block;overflow-x:auto}"
       "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}td:first-child{text-"
       "align:left}figure{margin:1em 0}svg{max-width:100%;height:auto}</style></head><body>\n";
  std::istringstream lines(md);
  std::string line;
  bool in_table = false, header = false, figures_done = false;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] == '|') {
      if (line.rfind("|---", 0) == 0) continue;
      if (!in_table) h << "<table>\n";
      header = !in_table;
      in_table = true;
      h << "<tr>";
      for (const auto& c : cells(line)) {
        h << (header ? "<th>" : "<td>") << html_escape(c) << (header ? "</th>" : "</td>");
      }
      h << "</tr>\n";
      continue;
    }
    if (in_table) {
      h << "</table>\n";
      in_table = false;
      if (!figures_done) h << figures;
      figures_done = true;
    }
    if (line.rfind("## ", 0) == 0) {
      h << "<h2>" << html_escape(line.substr(3)) << "</h2>\n";
    } else if (line.rfind("# ", 0) == 0) {
      h << "<h1>" << html_escape(line.substr(2)) << "</h1>\n";
    } else if (!line.empty()) {
      h << "<p>" << html_escape(line) << "</p>\n";
    }
  }
  if (in_table) h << "</table>\n";
  h << "</body></html>\n";
  return h.str();
}

}  // namespace

size_t chart_output(const DesignSensitivity& s, const std::string& name) {
  const auto it = std::find(s.outputs.begin(), s.outputs.end(), name);
  if (it == s.outputs.end()) {
    std::string known;
    for (const auto& o : s.outputs) known += (known.empty() ? "" : ", ") + o;
    throw io::InputError("--chart", "", "an output of the design (" + known + ")",
                         "\"" + name + "\"");
  }
  return static_cast<size_t>(it - s.outputs.begin());
}

void write_sensitivity(const DesignSensitivity& s, const std::string& dir,
                       const std::string& chart) {
  const size_t c = chart_output(s, chart);
  io::make_directories(dir);
  json doc = {{"type", "pronk sensitivity"},
              {"design", s.design_path},
              {"study", s.study},
              {"model", s.model},
              {"set", s.set},
              {"physical", s.plant ? "plant" : "design"},
              {"scenarios", s.scenarios},
              {"evaluations", s.evaluations},
              {"failed_evaluations", s.failed},
              {"failures", s.failures},
              {"inputs", inputs_json(s)},
              {"outputs", s.outputs},
              {"local", local_json(s)},
              {"sobol", sobol_json(s)},
              {"wall_time_s", {{"local", s.local_seconds}, {"sobol", s.sobol_seconds}}}};
  io::write_file_atomic(dir + "/sensitivity.json", doc.dump(1) + "\n");
  io::write_file_atomic(dir + "/local.csv", local_csv(s));
  io::write_file_atomic(dir + "/sobol.csv", sobol_csv(s));
  io::write_file_atomic(dir + "/tornado.csv", tornado_csv(s));
  io::write_file_atomic(dir + "/summary.md", summary_md(s, c));
  io::FigureBatch figures;
  tornado_figure(s, dir, c, figures);
  if (s.sobol) sobol_figure(s, dir, c, figures);
  figures.finish();  // the report holds the figures
  io::write_file_atomic(dir + "/report.html",
                        report_html(summary_md(s, c), dir, "Sensitivity of " + s.study));
}

}  // namespace pronk::optimize::sensitivity
