// The shard plan (gate_plan.hpp): longest-processing-time-first over the recorded part times.
#include "gate_plan.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

namespace ap::cli::gate_stages {
namespace {

// FNV-1a, 64 bit: the same digest in every process and on every machine (std::hash is neither).
std::string fnv1a(const std::string& s) {
  unsigned long long h = 1469598103934665603ULL;
  for (const char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", h);
  return buf;
}

}  // namespace

PartTimes parse_times(const std::string& text) {
  PartTimes t;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    std::string stage, name, secs;
    if (!std::getline(row, stage, '\t') || !std::getline(row, name, '\t') || !std::getline(row, secs)) continue;
    std::size_t used = 0;
    double s = -1;
    try {
      s = std::stod(secs, &used);
    } catch (...) {
      continue;
    }
    if (used != secs.size() || !(s >= 0)) continue;
    t[stage][name] = s;
  }
  return t;
}

Plan make_plan(const std::map<std::string, std::vector<std::string>>& parts, const PartTimes& times, int count) {
  Plan plan;
  for (const auto& [stage, names] : parts) {
    const auto known = times.find(stage);
    const std::set<std::string> listed(names.begin(), names.end());
    double sum = 0;
    int n = 0;
    if (known != times.end()) {
      for (const auto& [name, s] : known->second) {
        if (listed.count(name) != 0) {
          sum += s;
          ++n;
        }
      }
    }
    const double mean = n > 0 ? sum / n : 1.0;
    for (const auto& name : listed) {
      double s = mean;
      if (known != times.end()) {
        const auto it = known->second.find(name);
        if (it != known->second.end()) s = it->second;
      }
      plan.parts.push_back({stage, name, s, 1});
    }
  }
  std::vector<std::size_t> order(plan.parts.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto& x = plan.parts[a];
    const auto& y = plan.parts[b];
    if (x.seconds != y.seconds) return x.seconds > y.seconds;
    return std::tie(x.stage, x.name) < std::tie(y.stage, y.name);
  });
  std::vector<double> load(static_cast<std::size_t>(std::clamp(count, 1, 64)), 0.0);
  for (const std::size_t k : order) {
    const auto least = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    plan.parts[k].shard = static_cast<int>(least) + 1;
    load[least] += plan.parts[k].seconds;
  }
  std::string all;
  for (const auto& p : plan.parts) all += p.stage + "\t" + p.name + "\t" + std::to_string(p.shard) + "\n";
  plan.digest = fnv1a(all);
  return plan;
}

std::string xml_unescape(const std::string& text) {
  static const std::pair<const char*, char> kEntities[] = {
      {"&quot;", '"'}, {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&apos;", '\''}};
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    bool replaced = false;
    if (text[i] == '&') {
      for (const auto& [entity, c] : kEntities) {
        if (text.compare(i, std::char_traits<char>::length(entity), entity) == 0) {
          out += c;
          i += std::char_traits<char>::length(entity);
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += text[i++];
  }
  return out;
}

}  // namespace ap::cli::gate_stages
