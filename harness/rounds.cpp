#include "harness/rounds.h"

namespace harness {

std::vector<std::size_t> round_order(std::size_t n, int round) {
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = round % 2 == 0 ? k : n - 1 - k;
  return order;
}

bool Rounds::run(const std::vector<std::size_t>& active, const std::function<std::optional<Sample>(std::size_t)>& time,
                 const std::function<bool()>& stop) {
  std::vector<std::optional<Sample>> round(n_);
  for (std::size_t k : round_order(active.size(), int(rounds_.size()))) {
    if (stop()) return false;
    round[active[k]] = time(active[k]);
  }
  rounds_.push_back(std::move(round));
  return true;
}

std::vector<Sample> Rounds::samples(std::size_t i) const {
  std::vector<Sample> out;
  for (const auto& r : rounds_)
    if (r[i]) out.push_back(*r[i]);
  return out;
}

std::pair<std::vector<double>, std::vector<double>> Rounds::paired_wall(std::size_t i, std::size_t j) const {
  std::pair<std::vector<double>, std::vector<double>> out;
  for (const auto& r : rounds_)
    if (r[i] && r[j]) {
      out.first.push_back(r[i]->wall_ms);
      out.second.push_back(r[j]->wall_ms);
    }
  return out;
}

std::vector<double> wall_times(const std::vector<Sample>& samples) {
  std::vector<double> out;
  for (const auto& s : samples) out.push_back(s.wall_ms);
  return out;
}

std::vector<double> cpu_times(const std::vector<Sample>& samples) {
  std::vector<double> out;
  for (const auto& s : samples) out.push_back(s.cpu_ms);
  return out;
}

}  // namespace harness
