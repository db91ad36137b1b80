// The network: nodes with a physical domain, and the elements between them.
//
// Firestone (mobility) analogy: across = voltage (velocity v [m/s], angular
// velocity Ω [rad/s], electric potential u [V]); through = current (force F [N], torque
// M [N·m], electric current i [A]). Node `ground` is the reference of every domain
// (v = 0: a clamp; Ω = 0; u = 0).
//
// A Network holds no analysis state. assemble() stamps every element once into the MNA form
//     C·y' + G·y + g(y) = b(t)
// with y = [node across values; branch unknowns]; analyses take the System and never look at
// element kinds.
//
// Ownership: elements are shared (std::shared_ptr), by the Network that holds them and by every
// System assembled from it (its nonlinear elements), so a System stays valid after its Network
// (or the Model around it) is gone; a copy of a Network shares its elements.
//
// What a sweep changes is kept apart from what it does not: the System's G, C and nonlinear
// elements are fixed by the network's structure; its Excitation (the source terms of b(t) with
// their waveforms, and the direct AC excitation) can be replaced on an assembled System
// (System::set_excitation) without assembling G and C again.
#pragma once

#include <Eigen/SparseCore>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "emnet/network/output.hpp"
#include "emnet/network/waveform.hpp"

namespace emnet {

/// The physical domain of a node or a through quantity.
enum class Domain { electrical, translational, rotational };
/// The domain's name as messages give it.
const char* domain_name(Domain domain);
/// "V", "m/s", "rad/s"
const char* across_unit(Domain domain);
/// "A", "N", "N*m"
const char* through_unit(Domain domain);
/// Whether `domain` is translational or rotational.
inline bool is_mechanical(Domain domain) {
  return domain != Domain::electrical;
}

/// A node's index in y.
using NodeId = int;
/// The reference node; not an unknown.
constexpr NodeId ground = -1;

/// One node of a Network.
struct Node {
  std::string name;     ///< short, SPICE-safe: "v3", "r3", "e_A"
  Domain domain;        ///< the domain of its across value
  std::string meaning;  ///< "velocity at x = 70.0 mm"
};

/// What one unknown of y is.
struct Unknown {
  std::string name;
  /// A node's across value, or a branch's through quantity.
  enum class Kind { node_across, branch_through } kind;
  Domain domain;  ///< of the node, or of the branch's through quantity
  /// For an error-controlled integrator (IDA): when > 0, this unknown is fixed by the
  /// mechanical displacements through a stiffness, and its absolute tolerance is the
  /// translational displacement's times this factor [unknown's unit per m] (a chord's change:
  /// 1; its angle: 1/l; a compliance's force: 1/n). Then an unknown that a stiff compliance
  /// amplifies (an axial force, EA/l times a chord's change) is held to what its displacement
  /// allows, not to the scale of the other forces, which no step could meet. 0: by its kind.
  double tolerance_per_displacement = 0.0;
  /// A branch unknown that is a geometric state, not a through quantity: a displacement [m]
  /// (translational) or an angle [rad] (rotational), as a co-rotational chord's change and angle.
  /// Reports group it apart from the forces.
  bool geometric = false;
};

class Stamper;

/// One network element. Elements stamp; analyses solve.
class Element {
 public:
  explicit Element(std::string name) : name_(std::move(name)) {}
  virtual ~Element() = default;
  const std::string& name() const { return name_; }
  /// The element's kind, e.g. "capacitor".
  virtual const char* kind() const = 0;
  /// Extra unknowns this element adds to y (branch currents), with their domain.
  virtual std::vector<Unknown> branch_unknowns() const { return {}; }
  /// Linear part (G, C), source terms b(t) and the AC excitation.
  virtual void stamp(Stamper& stamper) const = 0;
  /// Whether the element has a nonlinear part.
  virtual bool is_nonlinear() const { return false; }
  /// Nonlinear part: adds g(y) to `g` and, when `jacobian` is given, ∂g/∂y to it (as entries
  /// added into the triplet list). Linear elements do nothing.
  /// @param branch_offset  the index in y of the element's first branch unknown
  virtual void add_nonlinear(const Eigen::VectorXd& /*y*/, int /*branch_offset*/,
                             Eigen::VectorXd& /*g*/,
                             std::vector<Eigen::Triplet<double>>* /*jacobian*/) const {}
  /// A nonlinear part that is a source d·u² of one linear functional u of y, entering the rows
  /// of `direction` as g = −d·u² (a DEA's force k_F·u² without its back-coupling): u's terms
  /// and d's rows, for the exact periodic cascade. False for any other nonlinear part (the
  /// default) and for a linear element.
  /// @param voltage    u = Σ c·y[index] [V for a DEA]
  /// @param direction  d per row [N/V² for a DEA]
  virtual bool squared_source(LinearTerms& /*voltage*/, LinearTerms& /*direction*/) const {
    return false;
  }

 private:
  std::string name_;
};

class System;
struct Excitation;

/// Nodes and elements, assembled into a System.
class Network {
 public:
  /// Adds a node; returns its id.
  NodeId add_node(std::string name, Domain domain, std::string meaning);
  /// Adds an element made from `args`; returns it.
  template <class ElementType, class... Args>
  ElementType& add(Args&&... args) {
    auto element = std::make_shared<ElementType>(std::forward<Args>(args)...);
    ElementType& reference = *element;
    elements_.push_back(std::move(element));
    return reference;
  }
  const std::vector<Node>& nodes() const { return nodes_; }
  const Node& node(NodeId id) const { return nodes_.at(static_cast<size_t>(id)); }
  const std::vector<std::shared_ptr<Element>>& elements() const { return elements_; }
  /// The element named `name`; nullptr when there is none.
  const Element* find(const std::string& name) const;
  /// Index in y of the k-th branch unknown of element `element` (an index into elements()) as
  /// assemble() numbers them: after every node, in element order. Valid for the network as it
  /// is: a node added later moves every branch unknown (elements added later do not).
  /// @throws std::out_of_range when the element has no k-th branch unknown
  int branch_unknown_index(std::size_t element, int k = 0) const;

  /// The MNA system of the network.
  System assemble() const;
  /// The excitation alone, as assemble() stamps it (no G, no C).
  Excitation assemble_excitation() const;

 private:
  // Stamps every element into `system` (its unknowns numbered): the excitation always, G and C
  // when `matrices` is true.
  void stamp_elements(const std::vector<int>& offsets, System& system, bool matrices) const;

  std::vector<Node> nodes_;
  std::vector<std::shared_ptr<Element>> elements_;
};

/// What drives the system: b(t) = Σ coefficient·waveforms[w].value(t)·e_row over the source
/// terms, and the AC right-hand side b_ac = Σ coefficient·waveforms[w].ac_phasor()·e_row + ac.
struct Excitation {
  /// coefficient·waveforms[waveform].value(t) added to b[row].
  struct SourceTerm {
    int row;
    double coefficient;
    int waveform;  ///< index into waveforms
  };
  std::vector<Waveform> waveforms;
  /// The element (index into Network::elements()) whose stamp added each waveform.
  std::vector<int> waveform_element;
  std::vector<SourceTerm> source_terms;
  Eigen::VectorXcd ac;  ///< direct AC excitation stamped by elements
};

/// The assembled MNA system. Built once; every analysis reads it.
class System {
 public:
  /// The number of unknowns.
  int size() const { return static_cast<int>(unknowns.size()); }

  std::vector<Unknown> unknowns;  ///< what each entry of y is
  Eigen::SparseMatrix<double> G;  ///< conductance / stiffness-like part
  Eigen::SparseMatrix<double> C;  ///< capacitance / mass-like part
  /// Elements with a nonlinear part g(y), shared with the Network they came from.
  std::vector<std::shared_ptr<const Element>> nonlinear_elements;
  /// The index in y of each nonlinear element's first branch unknown, as nonlinear_elements.
  std::vector<int> nonlinear_branch_offsets;

  using SourceTerm = Excitation::SourceTerm;
  /// The sources: stamped by assemble(), replaced only through set_excitation, which checks it.
  const Excitation& excitation() const { return excitation_; }

  /// A new excitation for the same G, C and nonlinear elements (a sweep's next frequency).
  /// @throws std::invalid_argument when it does not fit the system (size, rows, waveforms)
  void set_excitation(Excitation replacement);
  /// A copy with `replacement` set as by set_excitation.
  /// @throws std::invalid_argument when it does not fit the system
  System with_excitation(Excitation replacement) const;

  /// The right-hand side b(t) of the sources; t [s].
  Eigen::VectorXd b(double t) const;
  /// b(0).
  Eigen::VectorXd b_at_rest() const { return b(0.0); }
  /// db/dt on the source pieces that hold t (Waveform::slope): zero for piecewise-constant
  /// sources, so that b(t₀) + b_slope(t)·(t − t₀) is b on a piece of piecewise-linear ones.
  Eigen::VectorXd b_slope(double t) const;
  /// AC right-hand side: source phasors plus the direct excitation.
  Eigen::VectorXcd b_ac() const;
  /// Whether any element has a nonlinear part.
  bool is_nonlinear() const { return !nonlinear_elements.empty(); }
  /// g(y) and, optionally, its Jacobian.
  void nonlinear(const Eigen::VectorXd& y, Eigen::VectorXd& g,
                 Eigen::SparseMatrix<double>* jacobian) const;
  /// Instants in (t_begin, t_end] where a source jumps.
  std::vector<double> breakpoints(double t_begin, double t_end) const;
  /// Index of the first unknown belonging to each element's branch list, by element name.
  /// @throws std::out_of_range when no element is named `element_name`
  int branch_index(const std::string& element_name, int k = 0) const;
  /// (element name, index of its first branch unknown) for each element with branch unknowns.
  std::vector<std::pair<std::string, int>> branch_offsets;

 private:
  friend class Network;  // assembles it
  friend class Stamper;  // stamps the elements' sources into it
  Excitation excitation_;
};

/// Handed to Element::stamp. Rows/columns equal to `ground` are dropped.
class Stamper {
 public:
  /// @param branch_offset  the index in y of the element's first branch unknown
  Stamper(System& system, int branch_offset) : system_(system), branch_offset_(branch_offset) {}
  /// Adds `value` to G[row, column].
  void g(int row, int column, double value);
  /// Adds `value` to C[row, column].
  void c(int row, int column, double value);
  /// A two-terminal admittance between nodes a and b: +value on the diagonal, −value off it.
  void g_between(NodeId a, NodeId b, double value);
  /// The same on C.
  void c_between(NodeId a, NodeId b, double value);
  /// Adds coefficient·waveform(t) to b[row]; returns the waveform's index for reuse.
  int source(int row, double coefficient, const Waveform& waveform);
  /// Adds coefficient·waveform(t) to b[row] for a waveform already added.
  void source(int row, double coefficient, int waveform_index);
  /// Adds `value` to the direct AC excitation at `row`.
  void ac(int row, std::complex<double> value);
  /// Global index of this element's k-th branch unknown.
  int branch(int k) const { return branch_offset_ + k; }

  std::vector<Eigen::Triplet<double>> g_entries;  ///< G entries stamped so far
  std::vector<Eigen::Triplet<double>> c_entries;  ///< C entries stamped so far

 private:
  System& system_;
  int branch_offset_;
};

}  // namespace emnet
