// The mesher: see include/emnet/model/mesh.hpp.
#include "emnet/model/mesh.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
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
  // Large kinematics: a probe reads a node's own unknowns (no shape functions between nodes).
  if (scene.beam.kinematics == BeamKinematics::large)
    for (const ProbeSpec& probe : scene.probes)
      if (is_beam_motion(probe.quantity)) points.push_back(probe.at);
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
// whose segments are longest: the counts that make the longest segment shortest, a spread by
// length at every N. (Nested meshes for the N/2N estimates come from BeamSpec::refinement, not
// from spreading 2N as twice N, which gave 110/70/120 mm 64/64/64 at N = 192.)
void spread(std::vector<Interval*>& intervals, int total) {
  if (intervals.empty()) return;
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

namespace {

// The mesh of beam.segments by the header's rules 1 and 2, before BeamSpec::refinement.
BeamMesh spread_mesh(const BeamSpec& beam, const std::vector<double>& attachments) {
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

// Each segment of `mesh` cut into `parts` equal ones.
BeamMesh refine(const BeamMesh& mesh, int parts) {
  BeamMesh fine;
  fine.uniform = mesh.uniform;
  fine.raised_from = mesh.raised_from;
  fine.x.push_back(mesh.x.front());
  if (mesh.uniform) {  // still the uniform grid x_k = L·k/(parts·N), exactly
    const int total = parts * mesh.segments();
    for (int k = 1; k <= total; ++k) fine.x.push_back(mesh.x.back() * k / total);
    fine.section.assign(static_cast<size_t>(total), 0);
    return fine;
  }
  for (size_t k = 0; k + 1 < mesh.x.size(); ++k)
    for (int part = 1; part <= parts; ++part) {
      fine.x.push_back(part == parts ? mesh.x[k + 1]
                                     : mesh.x[k] + (mesh.x[k + 1] - mesh.x[k]) * part / parts);
      fine.section.push_back(mesh.section[k]);
    }
  return fine;
}

}  // namespace

BeamMesh mesh_beam(const BeamSpec& beam, const std::vector<double>& attachments) {
  if (beam.refinement < 1)
    throw std::logic_error("mesh_beam: refinement " + std::to_string(beam.refinement) + " < 1");
  BeamMesh mesh = spread_mesh(beam, attachments);
  if (beam.refinement > 1) mesh = refine(mesh, beam.refinement);
  // BeamMesh's invariants: nodes from 0 to L, strictly increasing; a section per segment.
  assert(mesh.x.size() >= 2 && mesh.x.front() == 0.0 &&
         std::abs(mesh.x.back() - beam.length) <=
             4 * std::numeric_limits<double>::epsilon() * beam.length);
  assert(std::is_sorted(mesh.x.begin(), mesh.x.end(), std::less_equal<double>()) &&
         std::adjacent_find(mesh.x.begin(), mesh.x.end()) == mesh.x.end());
  assert(mesh.section.size() + 1 == mesh.x.size());
  return mesh;
}

}  // namespace emnet
