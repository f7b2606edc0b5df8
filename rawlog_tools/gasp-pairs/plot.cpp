// gasp-pairs-plot: error against skip per method, from the CSV tables of gasp-pairs --csv.
//   gasp-pairs-plot --csv A.csv[,B.csv...] [--title "A title"...] --out FIGURE.png [--caption TEXT]
// One row of three panels per CSV: translational RMSE [m], rotational RMSE [deg] and failure rate
// [%] against skip, one coloured line per method (legend at the right). Skips are placed at even
// spacing in the order they appear. Exit codes: 0 done, 1 bad input, 2 usage error.
#include <CLI/CLI.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "cli.h"
#include "params_options.h"

namespace {

struct Row {
  std::size_t skip = 0;
  std::string method;
  double rmse_t = 0, rmse_r = 0, fail = 0;
};

std::vector<Row> readCsv(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw gasp::Error("cannot read " + path);
  std::string line;
  std::getline(f, line);
  if (line.rfind("skip,method,pairs,failed,rmse_t_m,rmse_r_deg,fail_pct", 0) != 0)
    throw gasp::Error(path + ":1: not a gasp-pairs --csv table");
  std::vector<Row> rows;
  int n = 1;
  while (std::getline(f, line)) {
    ++n;
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::vector<std::string> c;
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    if (c.size() < 7)
      throw gasp::Error(path + ":" + std::to_string(n) + ": expected the 9 columns of the header (got " +
                        std::to_string(c.size()) + ")");
    // A number, or NaN for an empty RMSE cell (every pair of that skip failed: nothing to plot).
    const auto number = [&](const std::string& cell, bool may_be_empty) {
      if (cell.empty() && may_be_empty) return std::numeric_limits<double>::quiet_NaN();
      double v = 0;
      try {
        std::size_t used = 0;
        v = std::stod(cell, &used);
        if (used != cell.size()) throw std::invalid_argument(cell);
      } catch (const std::exception&) {
        throw gasp::Error(path + ":" + std::to_string(n) + ": '" + cell + "' is not a number");
      }
      if (!std::isfinite(v)) throw gasp::Error(path + ":" + std::to_string(n) + ": '" + cell + "' is not finite");
      return v;
    };
    Row r;
    // A skip is a whole number >= 1 (std::stoul alone would take "-1" and wrap it round).
    const bool digits = !c[0].empty() && c[0].size() <= 9 &&
                        std::all_of(c[0].begin(), c[0].end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    if (!digits || std::stoul(c[0]) == 0)
      throw gasp::Error(path + ":" + std::to_string(n) + ": '" + c[0] + "' is not a skip (a whole number from 1)");
    r.skip = std::stoul(c[0]);
    r.method = c[1];
    if (r.method.empty()) throw gasp::Error(path + ":" + std::to_string(n) + ": the method is empty");
    for (const Row& earlier : rows)
      if (earlier.skip == r.skip && earlier.method == r.method)
        throw gasp::Error(path + ":" + std::to_string(n) + ": a second row for skip " + c[0] + " and method " +
                          r.method + " (one row each; were two tables joined?)");
    r.rmse_t = number(c[4], true);
    r.rmse_r = number(c[5], true);
    r.fail = number(c[6], false);
    rows.push_back(r);
  }
  if (rows.empty()) throw gasp::Error(path + ": no rows (only the header)");
  return rows;
}

const std::vector<cv::Scalar> kColours{{40, 40, 220}, {0, 140, 255}, {200, 120, 0}, {60, 170, 60},
                                       {170, 60, 170}, {150, 150, 0}, {90, 90, 90}, {0, 200, 200}};

std::string fmt(double v) {
  char b[32];
  // Two significant digits below 1, so that ticks 0.007 apart stay apart (not "0.01, 0.01").
  std::snprintf(b, sizeof b, v == 0 ? "0" : v < 1 ? "%.2g" : v < 10 ? "%.1f" : "%.0f", v);
  return b;
}

/// One panel: value against skip index, one line per method.
void panel(cv::Mat& img, cv::Rect box, const std::string& title, const std::vector<std::size_t>& skips,
           const std::vector<std::string>& methods, const std::vector<Row>& rows, double Row::*field) {
  const int left = 50, bottom = 36, top = 26, right = 12;
  const cv::Rect plot(box.x + left, box.y + top, box.width - left - right, box.height - top - bottom);
  double vmax = 0;
  for (const auto& r : rows)
    if (std::isfinite(r.*field)) vmax = std::max(vmax, r.*field);
  vmax = vmax > 0 ? vmax * 1.1 : 1.0;
  cv::rectangle(img, plot, cv::Scalar(0, 0, 0), 1);
  cv::putText(img, title, {box.x + left, box.y + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  for (int k = 0; k <= 4; ++k) {
    const double v = vmax * k / 4;
    const int y = plot.y + plot.height - static_cast<int>(std::lround(plot.height * k / 4.0));
    cv::line(img, {plot.x - 4, y}, {plot.x, y}, cv::Scalar(0, 0, 0));
    cv::line(img, {plot.x + 1, y}, {plot.x + plot.width - 1, y}, cv::Scalar(225, 225, 225));
    cv::putText(img, fmt(v), {box.x + 4, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.38, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  auto xOf = [&](std::size_t k) {
    return plot.x + static_cast<int>(std::lround(plot.width * (k + 0.5) / static_cast<double>(skips.size())));
  };
  for (std::size_t k = 0; k < skips.size(); ++k) {
    cv::line(img, {xOf(k), plot.y + plot.height}, {xOf(k), plot.y + plot.height + 4}, cv::Scalar(0, 0, 0));
    cv::putText(img, std::to_string(skips[k]), {xOf(k) - 8, plot.y + plot.height + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.42,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  cv::putText(img, "skip", {plot.x + plot.width / 2 - 12, box.y + box.height - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.42,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  for (std::size_t m = 0; m < methods.size(); ++m) {
    std::vector<cv::Point> pts;
    for (std::size_t k = 0; k < skips.size(); ++k)
      for (const auto& r : rows)
        if (r.method == methods[m] && r.skip == skips[k] && std::isfinite(r.*field))  // no RMSE: no point
          pts.emplace_back(xOf(k), plot.y + plot.height - static_cast<int>(std::lround(plot.height * (r.*field) / vmax)));
    const cv::Scalar c = kColours[m % kColours.size()];
    for (std::size_t p = 1; p < pts.size(); ++p) cv::line(img, pts[p - 1], pts[p], c, 2, cv::LINE_AA);
    for (const auto& p : pts) cv::circle(img, p, 4, c, cv::FILLED, cv::LINE_AA);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-pairs-plot: error against skip per method from gasp-pairs --csv tables"};
  // The params file is not used here; it is checked, and --print-params prints it, as in every program.
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  if (const int code = params_options.printBeforeParse(params); code >= 0) return code;
  params_options.add(app);
  std::vector<std::string> csvs, titles;
  std::string out, caption;
  app.add_option("--csv", csvs, "gasp-pairs --csv tables, one row of panels each")->required()->delimiter(',');
  app.add_option("--title", titles, "a title per CSV (default: the file name)");
  app.add_option("--out", out, "the PNG to write")->required()->check(gasp::tools::nonEmpty());
  app.add_option("--caption", caption, "a line at the bottom (e.g. the command that made the data)");
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;
  try {
    gasp::requireImageWriter(out, "--out figure");  // a usage error, before the work
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 2;
  }
  try {
    gasp::tools::RunOutputs outputs({{"--out", out}}, csvs);  // before the work
    const int panel_w = 330, panel_h = 230, legend_w = 165, row_title = 22;
    const int height = static_cast<int>(csvs.size()) * (panel_h + row_title) + (caption.empty() ? 8 : 30);
    cv::Mat img(height, 3 * panel_w + legend_w, CV_8UC3, cv::Scalar(255, 255, 255));
    for (std::size_t c = 0; c < csvs.size(); ++c) {
      const auto rows = readCsv(csvs[c]);
      std::vector<std::size_t> skips;
      std::vector<std::string> methods;
      for (const auto& r : rows) {
        if (std::find(skips.begin(), skips.end(), r.skip) == skips.end()) skips.push_back(r.skip);
        if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
      }
      const int y0 = static_cast<int>(c) * (panel_h + row_title);
      const std::string title = c < titles.size() ? titles[c] : csvs[c];
      cv::putText(img, title, {8, y0 + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
      panel(img, {0, y0 + row_title, panel_w, panel_h}, "translational RMSE [m]", skips, methods, rows, &Row::rmse_t);
      panel(img, {panel_w, y0 + row_title, panel_w, panel_h}, "rotational RMSE [deg]", skips, methods, rows, &Row::rmse_r);
      panel(img, {2 * panel_w, y0 + row_title, panel_w, panel_h}, "failures [%]", skips, methods, rows, &Row::fail);
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const cv::Point p(3 * panel_w + 10, y0 + row_title + 40 + static_cast<int>(m) * 22);
        cv::line(img, p, p + cv::Point(24, 0), kColours[m % kColours.size()], 2, cv::LINE_AA);
        cv::putText(img, methods[m], p + cv::Point(32, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
                    cv::LINE_AA);
      }
    }
    if (!caption.empty())
      cv::putText(img, caption, {8, height - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
    gasp::writeImage(outputs.at("--out"), img, "figure");
    std::printf("figure: %s\n", out.c_str());
  } catch (const std::exception& e) {  // gasp::Error, and anything a library throws
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
