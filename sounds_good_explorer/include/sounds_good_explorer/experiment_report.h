#pragma once

#include <string>
#include <vector>

#include "sounds_good_explorer/experiment.h"
#include "sounds_good_explorer/statistics.h"

namespace sounds_good_explorer {

// Tables and plots of an experiment's rows. A censored trial counts at the time cap (a lower
// bound of its real time) and every table says how many cells hold censored trials.
// Files: each writer throws std::runtime_error naming the path when it cannot write.

// trials.csv: config,mode,trial,seed,time_s,censored
void WriteTrialsCsv(const std::string& path, const std::vector<TrialRow>& rows);
// jobs.csv: config,mode,trial,job,robot,marker,time_s (every job of every trial)
void WriteJobsCsv(const std::string& path, const std::vector<TrialRow>& rows);

// Times of the trials of one configuration and mode.
std::vector<double> Times(const std::vector<TrialRow>& rows, int config, ListenMode mode);
int Censored(const std::vector<TrialRow>& rows, int config, ListenMode mode);

// Table 3.1 (mean and standard deviation per configuration and mode), Markdown.
std::string Table31(const std::vector<TrialRow>& rows, const std::vector<ListenMode>& modes,
                    int configs);
// Table 3.2 (gain and two-tailed t-test for every pair of modes on every configuration), Markdown.
std::string Table32(const std::vector<TrialRow>& rows, const std::vector<ListenMode>& modes,
                    int configs);
// Per pair of modes: in how many configurations the second was significantly (p < 0.05)
// faster, slower, or not different; then the configurations' tests combined (Stouffer:
// "combined B vs A: gain G % z Z p P", G the geometric mean of the per-configuration gains).
std::string Verdict(const std::vector<TrialRow>& rows, const std::vector<ListenMode>& modes,
                    int configs);

// Figure 3.6(b): mean and 95 % interval of the team time per configuration and mode, the
// configurations ordered by the first mode's mean (the thesis orders by "no audio").
void WriteTeamTimeChart(const std::string& path, const std::vector<TrialRow>& rows,
                        const std::vector<ListenMode>& modes, int configs);
// Figure 3.6(a): mean and 95 % interval of the time to each team job in one configuration.
void WriteJobTimeChart(const std::string& path, const std::vector<TrialRow>& rows,
                       const std::vector<ListenMode>& modes, int config, int jobs);

}  // namespace sounds_good_explorer
