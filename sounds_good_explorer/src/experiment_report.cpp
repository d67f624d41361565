#include "sounds_good_explorer/experiment_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "sounds_good_explorer/interval_chart.h"

namespace sounds_good_explorer {

namespace {

std::ofstream OpenFile(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  return out;
}

void Close(std::ofstream& out, const std::string& path) {
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed");
}

std::string Format(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string ConfigName(int config) {
  char text[16];
  std::snprintf(text, sizeof text, "#%02d", config);
  return text;
}

std::array<std::uint8_t, 3> ModeColour(ListenMode mode) {
  switch (mode) {
    case ListenMode::kNone: return {200, 60, 50};
    case ListenMode::kBidirectional: return {40, 110, 200};
    case ListenMode::kOmni: return {40, 160, 70};
  }
  return {0, 0, 0};
}

// The t-test of mode b against mode a on each configuration, 1..configs in order.
std::vector<TTest> PairTests(const std::vector<TrialRow>& rows, ListenMode a, ListenMode b,
                             int configs) {
  std::vector<TTest> tests;
  for (int c = 1; c <= configs; ++c) tests.push_back(StudentTTest(Times(rows, c, a), Times(rows, c, b)));
  return tests;
}

}  // namespace

void WriteTrialsCsv(const std::string& path, const std::vector<TrialRow>& rows) {
  std::ofstream out = OpenFile(path);
  out << "config,mode,trial,seed,time_s,censored\n";
  for (const TrialRow& r : rows)
    out << r.config << ',' << ListenModeName(r.mode) << ',' << r.trial << ',' << r.seed << ','
        << Format("%.2f", r.result.time) << ',' << (r.result.censored ? 1 : 0) << '\n';
  Close(out, path);
}

void WriteJobsCsv(const std::string& path, const std::vector<TrialRow>& rows) {
  std::ofstream out = OpenFile(path);
  out << "config,mode,trial,job,robot,marker,time_s\n";
  for (const TrialRow& r : rows)
    for (std::size_t j = 0; j < r.result.jobs.size(); ++j) {
      const JobRecord& job = r.result.jobs[j];
      out << r.config << ',' << ListenModeName(r.mode) << ',' << r.trial << ',' << j + 1 << ','
          << job.robot << ',' << job.marker << ',' << Format("%.2f", job.time) << '\n';
    }
  Close(out, path);
}

std::vector<double> Times(const std::vector<TrialRow>& rows, int config, ListenMode mode) {
  std::vector<double> times;
  for (const TrialRow& r : rows)
    if (r.config == config && r.mode == mode) times.push_back(r.result.time);
  return times;
}

int Censored(const std::vector<TrialRow>& rows, int config, ListenMode mode) {
  return static_cast<int>(std::count_if(rows.begin(), rows.end(), [&](const TrialRow& r) {
    return r.config == config && r.mode == mode && r.result.censored;
  }));
}

std::string Table31(const std::vector<TrialRow>& rows, const std::vector<ListenMode>& modes,
                    int configs) {
  std::ostringstream t;
  t << "| Config |";
  for (ListenMode m : modes) t << ' ' << ListenModeName(m) << " mean (s) | sd (s) |";
  t << "\n| --- |";
  for (std::size_t k = 0; k < modes.size(); ++k) t << " ---: | ---: |";
  t << '\n';
  int censored_total = 0;
  for (int c = 1; c <= configs; ++c) {
    t << "| " << ConfigName(c) << " |";
    for (ListenMode m : modes) {
      const SampleSummary s = Summarize(Times(rows, c, m));
      const int censored = Censored(rows, c, m);
      censored_total += censored;
      t << ' ' << Format("%.1f", s.mean) << (censored ? " (" + std::to_string(censored) + " censored)" : "")
        << " | " << Format("%.1f", s.sd) << " |";
    }
    t << '\n';
  }
  if (censored_total)
    t << "\nCensored trials (not finished within the time cap) count at the cap: their means are lower bounds.\n";
  return t.str();
}

std::string Table32(const std::vector<TrialRow>& rows, const std::vector<ListenMode>& modes,
                    int configs) {
  std::ostringstream t;
  t << "| Method 1 | Method 2 | Config | Perf. gain % | t | Significance % | Different? |\n"
       "| --- | --- | --- | ---: | ---: | ---: | --- |\n";
  for (std::size_t a = 0; a < modes.size(); ++a)
    for (std::size_t b = a + 1; b < modes.size(); ++b) {
      const std::vector<TTest> tests = PairTests(rows, modes[a], modes[b], configs);
      for (int c = 1; c <= configs; ++c) {
        const TTest& test = tests[c - 1];
        t << "| " << ListenModeName(modes[a]) << " | " << ListenModeName(modes[b]) << " | "
          << ConfigName(c) << " | " << Format("%.1f", 100.0 * test.gain) << " | "
          << Format("%.1f", test.t) << " | " << Format("%.3f", 100.0 * test.p) << " | "
          << (test.p < 0.05 ? "Yes" : "No") << " |\n";
      }
    }
  int censored = 0;
  for (const TrialRow& r : rows) censored += r.result.censored;
  if (censored)
    t << "\n" << censored << " censored trials enter the tests at the time cap (a lower bound).\n";
  return t.str();
}

std::string Verdict(const std::vector<TrialRow>& rows, const std::vector<ListenMode>& modes,
                    int configs) {
  std::ostringstream t;
  for (std::size_t a = 0; a < modes.size(); ++a)
    for (std::size_t b = a + 1; b < modes.size(); ++b) {
      const std::vector<TTest> tests = PairTests(rows, modes[a], modes[b], configs);
      int faster = 0, slower = 0;  // the second mode against the first
      for (const TTest& test : tests)
        if (test.p < 0.05) (test.t > 0 ? faster : slower) += 1;
      t << ListenModeName(modes[b]) << " vs " << ListenModeName(modes[a]) << ": significantly faster in "
        << faster << "/" << configs << ", significantly slower in " << slower << "/" << configs
        << ", not different in " << configs - faster - slower << "/" << configs << '\n';
      const CombinedTest combined = Stouffer(tests);
      t << "combined " << ListenModeName(modes[b]) << " vs " << ListenModeName(modes[a]) << ": gain "
        << Format("%.1f", 100.0 * combined.gain) << " % z " << Format("%.2f", combined.z) << " p "
        << Format("%.6f", combined.p) << '\n';
    }
  return t.str();
}

void WriteTeamTimeChart(const std::string& path, const std::vector<TrialRow>& rows,
                        const std::vector<ListenMode>& modes, int configs) {
  std::vector<double> first_mean(configs + 1);
  for (int c = 1; c <= configs; ++c) first_mean[c] = Summarize(Times(rows, c, modes.front())).mean;
  std::vector<int> order(configs);
  std::iota(order.begin(), order.end(), 1);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return first_mean[a] < first_mean[b]; });
  IntervalChart chart;
  chart.title = "Time to finish all jobs: mean and 95% interval per configuration";
  chart.x_label = std::string("configuration (ordered by ") + ListenModeName(modes.front()) + ")";
  chart.y_label = "team time (s)";
  for (int c : order) chart.x_ticks.push_back(ConfigName(c));
  for (ListenMode m : modes) {
    IntervalSeries s{ListenModeName(m), ModeColour(m), {}, {}};
    for (int c : order) {
      const SampleSummary summary = Summarize(Times(rows, c, m));
      s.mean.push_back(summary.mean);
      s.half_width.push_back(summary.ci95);
    }
    chart.series.push_back(s);
  }
  WriteIntervalChart(path, chart);
}

void WriteJobTimeChart(const std::string& path, const std::vector<TrialRow>& rows,
                       const std::vector<ListenMode>& modes, int config, int jobs) {
  IntervalChart chart;
  // A censored trial has no time for the jobs it did not reach: each job's mean is over the
  // trials that reached it (the title says so when any did not).
  chart.title = "Time to each team job in configuration " + ConfigName(config) +
                ": mean and 95% interval";
  if (std::any_of(rows.begin(), rows.end(), [&](const TrialRow& r) {
        return r.config == config && r.result.censored;
      }))
    chart.title += " (of the trials that reached each job)";
  chart.x_label = "job";
  chart.y_label = "time (s)";
  for (int j = 1; j <= jobs; ++j) chart.x_ticks.push_back(std::to_string(j));
  for (ListenMode m : modes) {
    IntervalSeries s{ListenModeName(m), ModeColour(m), {}, {}};
    for (int j = 1; j <= jobs; ++j) {
      std::vector<double> times;
      for (const TrialRow& r : rows)
        if (r.config == config && r.mode == m && static_cast<int>(r.result.jobs.size()) >= j)
          times.push_back(r.result.jobs[j - 1].time);
      const SampleSummary summary = Summarize(times);
      s.mean.push_back(times.empty() ? std::nan("") : summary.mean);
      s.half_width.push_back(summary.ci95);
    }
    chart.series.push_back(s);
  }
  WriteIntervalChart(path, chart);
}

}  // namespace sounds_good_explorer
