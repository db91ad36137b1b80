// The mesher: see include/emnet/model/mesh.hpp.
#include "emnet/model/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

namespace emnet {

std::vector<double> scene_attachment_points(const Scene& scene) {
  std::vector<double> points;
  for (const DeaSpec& dea : scene.deas) {
    points.push_back(dea.from);
    points.push_back(dea.to);
  }
  for (const LoadSpec& load : scene.loads) points.push_back(load.at);
  return points;
}

namespace {

// Sorted, without repeats closer than `merge` (the first of a close pair is kept).
std::vector<double> sorted_unique(std::vector<double> points, double merge) {
  std::sort(points.begin(), points.end());
  std::vector<double> unique;
  for (double point : points)
    if (unique.empty() || point - unique.back() > merge) unique.push_back(point);
  return unique;
}

struct Interval {
  double from = 0.0, to = 0.0;
  int section = 0;
  int segments = 1;
  double length() const { return to - from; }
};

// Gives `total` segments (at least one each) to `intervals`, each further one to the interval
// whose segments are longest. An even total that could be halved is twice the half's spread, so
// that doubling N halves every segment (the N/2N error estimates compare nested meshes).
void spread(std::vector<Interval*>& intervals, int total) {
  if (intervals.empty()) return;
  if (total % 2 == 0 && total / 2 >= static_cast<int>(intervals.size())) {
    spread(intervals, total / 2);
    for (Interval* interval : intervals) interval->segments *= 2;
    return;
  }
  for (Interval* interval : intervals) interval->segments = 1;
  int remaining = total - static_cast<int>(intervals.size());
  auto longer = [](const Interval* a, const Interval* b) {
    return a->length() / a->segments < b->length() / b->segments;
  };
  std::priority_queue<Interval*, std::vector<Interval*>, decltype(longer)> queue(longer, intervals);
  while (remaining-- > 0) {
    Interval* widest = queue.top();
    queue.pop();
    ++widest->segments;
    queue.push(widest);
  }
}

}  // namespace

BeamMesh mesh_beam(const BeamSpec& beam, const std::vector<double>& attachments) {
  const double length = beam.length;
  const std::vector<SectionSpec> sections = effective_sections(beam);
  const double merge = 1e-9 * length;
  // Section boundaries, the last one exactly the beam's end.
  std::vector<double> boundaries = {0.0};
  for (const SectionSpec& section : sections)
    boundaries.push_back(boundaries.back() + section.length);
  if (std::abs(boundaries.back() - length) > merge)
    throw std::logic_error("mesh_beam: the sections add up to " +
                           std::to_string(boundaries.back()) + " m, not the beam's length " +
                           std::to_string(length) + " m");
  boundaries.back() = length;

  std::vector<double> points = attachments;
  for (const MassSpec& mass : beam.masses) points.push_back(mass.at);
  for (const SpringSpec& spring : beam.springs) {
    points.push_back(spring.at);
    if (spring.to) points.push_back(*spring.to);
  }
  for (double& point : points) point = std::clamp(point, 0.0, length);

  const int wanted = beam.segments;
  int fixed = 0;
  for (const SectionSpec& section : sections) fixed += section.segments;
  if (wanted < 1 && fixed < 1) throw std::logic_error("mesh_beam: the beam has no segments");

  BeamMesh mesh;
  // Rule 1: the uniform grid, when it holds every attachment.
  if (sections.size() == 1 && sections[0].segments == 0) {
    bool on_grid = true;
    for (double point : points) {
      const double k = std::round(point / length * wanted);
      if (std::abs(point - length * k / wanted) > merge) on_grid = false;
    }
    if (on_grid) {
      for (int k = 0; k <= wanted; ++k) mesh.x.push_back(length * k / wanted);
      mesh.section.assign(static_cast<size_t>(wanted), 0);
      mesh.uniform = true;
      return mesh;
    }
  }

  // Rule 2: intervals between consecutive cuts, section by section.
  std::vector<double> cuts = boundaries;
  cuts.insert(cuts.end(), points.begin(), points.end());
  cuts = sorted_unique(cuts, merge);
  cuts.back() = length;
  std::vector<Interval> intervals;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    Interval interval{cuts[k], cuts[k + 1], 0, 1};
    const double middle = 0.5 * (interval.from + interval.to);
    while (interval.section + 1 < static_cast<int>(sections.size()) &&
           middle > boundaries[static_cast<size_t>(interval.section) + 1])
      ++interval.section;
    intervals.push_back(interval);
  }
  std::vector<Interval*> shared;
  int total = 0;
  for (size_t s = 0; s < sections.size(); ++s) {
    std::vector<Interval*> own;
    for (Interval& interval : intervals)
      if (interval.section == static_cast<int>(s)) own.push_back(&interval);
    if (sections[s].segments > 0) {
      const int count = std::max(sections[s].segments, static_cast<int>(own.size()));
      spread(own, count);
      total += count;
    } else {
      shared.insert(shared.end(), own.begin(), own.end());
    }
  }
  const int shared_count = std::max(wanted - fixed, static_cast<int>(shared.size()));
  if (!shared.empty()) {
    spread(shared, shared_count);
    total += shared_count;
  }
  const int asked = wanted > 0 ? wanted : fixed;
  if (total > asked) mesh.raised_from = asked;

  mesh.x.push_back(0.0);
  for (const Interval& interval : intervals) {
    for (int k = 1; k <= interval.segments; ++k) {
      mesh.x.push_back(k == interval.segments
                           ? interval.to
                           : interval.from + interval.length() * k / interval.segments);
      mesh.section.push_back(interval.section);
    }
  }
  return mesh;
}

}  // namespace emnet
