// Where the beam's nodes go: the mesher.
//
// A node is put at every position where something attaches to the beam — every section
// boundary, point mass, spring end, DEA end and load — so that no attachment sits inside a
// segment; the remaining segments are spread by length. Probes need no node: inside a massless
// segment the deflection is exactly the segment's shape function of its end values (Hermite for
// Euler–Bernoulli, the shear-corrected cubic for Timoshenko, emnet/model/model.hpp), so a probe
// reads it anywhere.
//
// Rule, for N = beam.segments:
//   1. The uniform grid x_k = L·k/N when it already holds every attachment (to 1e-9·L) and the
//      beam is one section without its own segment count: the beam of N equal segments.
//   2. Otherwise the attachments cut each section into intervals. A section with its own
//      section[].segments spreads that many (at least one per interval) over its intervals; the
//      other sections share the rest of N (at least one segment per interval). Within a share,
//      each further segment goes to the interval whose segments are longest (the smallest
//      largest segment for the count), and an interval's segments are equal: a spread by length
//      at every N.
//   3. BeamSpec::refinement > 1 cuts each segment of that mesh into as many equal ones: the
//      nested finer mesh of the N/2N error estimates (every node of N is a node of 2N).
// The total can exceed beam.segments when there are more intervals than segments; the mesh says
// so (BeamMesh::raised_from).
#pragma once

#include <string>
#include <vector>

#include "emnet/scene/scene.hpp"

namespace emnet {

/// The nodes of a beam and the section of each segment.
struct BeamMesh {
  std::vector<double> x;     ///< node positions [m], x.front() = 0, x.back() = beam.length
  std::vector<int> section;  ///< per segment: its index in effective_sections(beam)
  /// The uniform grid of rule 1 (segment length exactly beam.length / N, before refinement).
  bool uniform = false;
  /// beam.segments when the attachments needed more segments than it gives; else 0.
  int raised_from = 0;
  /// The number of segments N.
  int segments() const { return static_cast<int>(x.size()) - 1; }
};

/// The positions of the scene's attachments that are not part of the beam itself: DEA ends and
/// loads (the beam's masses, springs and sections are in its BeamSpec), and with large kinematics
/// the beam probes' positions.
std::vector<double> scene_attachment_points(const Scene& scene);

/// The nodes of `beam` with beam.segments segments (the resolved count; > 0) and a node at each
/// of `attachments` and of the beam's own sections, masses and springs.
/// @param attachments  positions along the beam [m]
/// @throws std::logic_error for a beam without segments, sections that do not add up to its
///         length, or a refinement below 1
BeamMesh mesh_beam(const BeamSpec& beam, const std::vector<double>& attachments);

}  // namespace emnet
