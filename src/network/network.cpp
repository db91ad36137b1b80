// Network bookkeeping and assembly of the MNA system C·y' + G·y + g(y) = b(t).
#include "emnet/network/network.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

namespace emnet {

const char* domain_name(Domain domain) {
  switch (domain) {
    case Domain::electrical:
      return "electrical";
    case Domain::translational:
      return "translational";
    case Domain::rotational:
      return "rotational";
  }
  return "?";
}
const char* across_unit(Domain domain) {
  switch (domain) {
    case Domain::electrical:
      return "V";
    case Domain::translational:
      return "m/s";
    case Domain::rotational:
      return "rad/s";
  }
  return "?";
}
const char* through_unit(Domain domain) {
  switch (domain) {
    case Domain::electrical:
      return "A";
    case Domain::translational:
      return "N";
    case Domain::rotational:
      return "N*m";
  }
  return "?";
}

NodeId Network::add_node(std::string name, Domain domain, std::string meaning) {
  nodes_.push_back({std::move(name), domain, std::move(meaning)});
  return static_cast<NodeId>(nodes_.size()) - 1;
}

const Element* Network::find(const std::string& name) const {
  for (const auto& element : elements_)
    if (element->name() == name) return element.get();
  return nullptr;
}

int Network::branch_unknown_index(std::size_t element, int k) const {
  if (element >= elements_.size() ||
      k >= static_cast<int>(elements_[element]->branch_unknowns().size()) || k < 0)
    throw std::out_of_range("branch_unknown_index: element " + std::to_string(element) +
                            " has no branch unknown " + std::to_string(k));
  int index = static_cast<int>(nodes_.size());
  for (std::size_t e = 0; e < element; ++e)
    index += static_cast<int>(elements_[e]->branch_unknowns().size());
  return index + k;
}

namespace {

// The unknowns of `nodes` and `elements` into `system`; the first branch unknown of each
// element (its offset) returned.
std::vector<int> number_unknowns(const std::vector<Node>& nodes,
                                 const std::vector<std::shared_ptr<Element>>& elements,
                                 System& system) {
  for (const auto& node : nodes)
    system.unknowns.push_back({node.name, Unknown::Kind::node_across, node.domain});
  std::vector<int> offsets;
  for (const auto& element : elements) {
    offsets.push_back(system.size());
    system.branch_offsets.emplace_back(element->name(), system.size());
    for (auto& unknown : element->branch_unknowns()) system.unknowns.push_back(unknown);
  }
  return offsets;
}

}  // namespace

// Stamps every element into `system` (whose unknowns are set): its excitation
// always, G and C when `matrices` is true, with the waveforms' owning elements recorded.
void Network::stamp_elements(const std::vector<int>& offsets, System& system, bool matrices) const {
  const auto& elements = elements_;
  const int n = system.size();
  system.excitation_.ac = Eigen::VectorXcd::Zero(n);
  std::vector<Eigen::Triplet<double>> g_entries, c_entries;
  for (size_t k = 0; k < elements.size(); ++k) {
    Stamper stamper(system, offsets[k]);
    elements[k]->stamp(stamper);
    system.excitation_.waveform_element.resize(system.excitation_.waveforms.size(),
                                               static_cast<int>(k));
    if (!matrices) continue;
    g_entries.insert(g_entries.end(), stamper.g_entries.begin(), stamper.g_entries.end());
    c_entries.insert(c_entries.end(), stamper.c_entries.begin(), stamper.c_entries.end());
    if (elements[k]->is_nonlinear()) {
      system.nonlinear_elements.push_back(elements[k]);
      system.nonlinear_branch_offsets.push_back(offsets[k]);
    }
  }
  if (!matrices) return;
  system.G.resize(n, n);
  system.C.resize(n, n);
  system.G.setFromTriplets(g_entries.begin(), g_entries.end());
  system.C.setFromTriplets(c_entries.begin(), c_entries.end());
  system.G.prune(0.0);
  system.C.prune(0.0);
  system.G.makeCompressed();
  system.C.makeCompressed();
}

System Network::assemble() const {
  System system;
  const std::vector<int> offsets = number_unknowns(nodes_, elements_, system);
  stamp_elements(offsets, system, true);
  return system;
}

Excitation Network::assemble_excitation() const {
  System system;
  const std::vector<int> offsets = number_unknowns(nodes_, elements_, system);
  stamp_elements(offsets, system, false);
  return std::move(system.excitation_);
}

void System::set_excitation(Excitation replacement) {
  const auto waveform_count = static_cast<int>(replacement.waveforms.size());
  if (replacement.ac.size() != size())
    throw std::invalid_argument("excitation: AC vector of size " +
                                std::to_string(replacement.ac.size()) + " for a system of " +
                                std::to_string(size()) + " unknowns");
  for (const auto& term : replacement.source_terms)
    if (term.row < 0 || term.row >= size() || term.waveform < 0 || term.waveform >= waveform_count)
      throw std::invalid_argument("excitation: a source term outside the system (row " +
                                  std::to_string(term.row) + ", waveform " +
                                  std::to_string(term.waveform) + ")");
  excitation_ = std::move(replacement);
}

System System::with_excitation(Excitation replacement) const {
  System copy = *this;
  copy.set_excitation(std::move(replacement));
  return copy;
}

Eigen::VectorXd System::b(double t) const {
  const auto& waveforms = excitation_.waveforms;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size());
  std::vector<double> values(waveforms.size());
  for (size_t w = 0; w < waveforms.size(); ++w) values[w] = waveforms[w].value(t);
  for (const auto& term : excitation_.source_terms)
    rhs[term.row] += term.coefficient * values[term.waveform];
  return rhs;
}

Eigen::VectorXd System::b_slope(double t) const {
  const auto& waveforms = excitation_.waveforms;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size());
  std::vector<double> slopes(waveforms.size());
  for (size_t w = 0; w < waveforms.size(); ++w) slopes[w] = waveforms[w].slope(t);
  for (const auto& term : excitation_.source_terms)
    rhs[term.row] += term.coefficient * slopes[term.waveform];
  return rhs;
}

Eigen::VectorXcd System::b_ac() const {
  Eigen::VectorXcd rhs = excitation_.ac;
  for (const auto& term : excitation_.source_terms)
    rhs[term.row] += term.coefficient * excitation_.waveforms[term.waveform].ac_phasor();
  return rhs;
}

void System::nonlinear(const Eigen::VectorXd& y, Eigen::VectorXd& g,
                       Eigen::SparseMatrix<double>* jacobian) const {
  g = Eigen::VectorXd::Zero(size());
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t k = 0; k < nonlinear_elements.size(); ++k)
    nonlinear_elements[k]->add_nonlinear(y, nonlinear_branch_offsets[k], g,
                                         jacobian ? &entries : nullptr);
  if (jacobian) {
    jacobian->resize(size(), size());
    jacobian->setFromTriplets(entries.begin(), entries.end());
  }
}

std::vector<double> System::breakpoints(double t_begin, double t_end) const {
  std::vector<double> out;
  for (const auto& waveform : excitation_.waveforms) waveform.breakpoints(t_begin, t_end, out);
  std::sort(out.begin(), out.end());
  // Edges of different sources meant to coincide (A off, B on) may differ by rounding:
  // they are one breakpoint, not an interval of a few ulps.
  const double merge = 1e-12 * std::max({1e-300, std::abs(t_begin), std::abs(t_end)});
  out.erase(
      std::unique(out.begin(), out.end(), [merge](double a, double b) { return b - a <= merge; }),
      out.end());
  return out;
}

int System::branch_index(const std::string& element_name, int k) const {
  for (const auto& [name, offset] : branch_offsets)
    if (name == element_name) return offset + k;
  throw std::out_of_range("no element named '" + element_name + "'");
}

void Stamper::g(int row, int column, double value) {
  if (row == ground || column == ground || value == 0.0) return;
  g_entries.emplace_back(row, column, value);
}

void Stamper::c(int row, int column, double value) {
  if (row == ground || column == ground || value == 0.0) return;
  c_entries.emplace_back(row, column, value);
}

void Stamper::g_between(NodeId a, NodeId b, double value) {
  g(a, a, value);
  g(b, b, value);
  g(a, b, -value);
  g(b, a, -value);
}

void Stamper::c_between(NodeId a, NodeId b, double value) {
  c(a, a, value);
  c(b, b, value);
  c(a, b, -value);
  c(b, a, -value);
}

int Stamper::source(int row, double coefficient, const Waveform& waveform) {
  system_.excitation_.waveforms.push_back(waveform);
  const int index = static_cast<int>(system_.excitation_.waveforms.size()) - 1;
  source(row, coefficient, index);
  return index;
}

void Stamper::source(int row, double coefficient, int waveform_index) {
  assert(waveform_index >= 0 &&
         waveform_index < static_cast<int>(system_.excitation_.waveforms.size()));
  if (row == ground || coefficient == 0.0) return;
  system_.excitation_.source_terms.push_back({row, coefficient, waveform_index});
}

void Stamper::ac(int row, std::complex<double> value) {
  if (row == ground) return;
  system_.excitation_.ac[row] += value;
}

}  // namespace emnet
