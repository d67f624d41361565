#include "audio_propagation/coupled_rooms.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace audio_propagation {
namespace {

std::string RoomName(const std::vector<CoupledRoomSpec>& rooms, std::size_t i) {
  return "room " + std::to_string(i) + (rooms[i].name.empty() ? "" : " ('" + rooms[i].name + "')");
}

void Validate(const std::vector<CoupledRoomSpec>& rooms, const std::vector<RoomOpening>& openings) {
  if (rooms.empty()) throw std::invalid_argument("coupled rooms: no rooms");
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    if (!(rooms[i].volume > 0.0) || !std::isfinite(rooms[i].volume)) {
      throw std::invalid_argument("coupled rooms: " + RoomName(rooms, i) + ".volume must be above 0 m^3, got " +
                                  std::to_string(rooms[i].volume));
    }
    if (!(rooms[i].rt60 > 0.0 && rooms[i].rt60 <= 20.0)) {
      throw std::invalid_argument("coupled rooms: " + RoomName(rooms, i) + ".rt60 must be in (0, 20] s, got " +
                                  std::to_string(rooms[i].rt60));
    }
  }
  for (std::size_t k = 0; k < openings.size(); ++k) {
    const RoomOpening& o = openings[k];
    const std::string what = "coupled rooms: opening " + std::to_string(k);
    if (o.a >= rooms.size() || o.b >= rooms.size()) {
      throw std::invalid_argument(what + " joins rooms " + std::to_string(o.a) + " and " + std::to_string(o.b) +
                                  ", but there are " + std::to_string(rooms.size()));
    }
    if (o.a == o.b) throw std::invalid_argument(what + " joins " + RoomName(rooms, o.a) + " to itself");
    if (!(o.area > 0.0) || !std::isfinite(o.area)) {
      throw std::invalid_argument(what + ".area must be above 0 m^2, got " + std::to_string(o.area));
    }
  }
}

}  // namespace

double SabineAbsorption(double volume, double rt60) { return 24.0 * std::log(10.0) * volume / (kSoundSpeed * rt60); }

CoupledRooms::CoupledRooms(std::vector<CoupledRoomSpec> rooms, std::vector<RoomOpening> openings)
    : rooms_(std::move(rooms)), openings_(std::move(openings)) {
  Validate(rooms_, openings_);
  const auto n = static_cast<Eigen::Index>(rooms_.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    absorption_.push_back(SabineAbsorption(rooms_[i].volume, rooms_[i].rt60));
    m(i, i) = absorption_.back();
  }
  for (const RoomOpening& o : openings_) {
    const auto a = static_cast<Eigen::Index>(o.a), b = static_cast<Eigen::Index>(o.b);
    m(a, a) += o.area;
    m(b, b) += o.area;
    m(a, b) -= o.area;
    m(b, a) -= o.area;
  }
  // M is symmetric and strictly diagonally dominant (every room absorbs something), so it is
  // positive definite: the inverse exists and every entry of it is positive.
  inverse_ = m.inverse();
  root_d_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) root_d_(i) = std::sqrt(kSoundSpeed / (4.0 * rooms_[i].volume));
  const Eigen::MatrixXd symmetric = root_d_.asDiagonal() * m * root_d_.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(symmetric);
  modes_ = solver.eigenvectors();
  mode_rates_ = solver.eigenvalues();
  rates_.assign(mode_rates_.data(), mode_rates_.data() + n);
  std::sort(rates_.begin(), rates_.end());
}

double CoupledRooms::RelativeLevelDb(std::size_t source, std::size_t listener) const {
  if (openings_.empty() && source == listener) return 0.0;  // exactly the single diffuse room
  const auto s = static_cast<Eigen::Index>(source), l = static_cast<Eigen::Index>(listener);
  // Rooms no chain of openings joins share no energy: the entry is 0 (or a rounding error's
  // worth), which is held at kNoCouplingDb rather than -inf, whose arithmetic downstream (a DRR
  // of +inf against a table) would be NaN.
  return std::max(kNoCouplingDb, 10.0 * std::log10(std::max(absorption_[source] * inverse_(l, s), 0.0)));
}

double CoupledRooms::DecayDb(std::size_t source, std::size_t listener, double t) const {
  const auto s = static_cast<Eigen::Index>(source), l = static_cast<Eigen::Index>(listener);
  // The steady energies relative to the source room shut: A_s M^-1 e_s.
  const Eigen::VectorXd steady = absorption_[source] * inverse_.col(s);
  const Eigen::VectorXd in_modes = modes_.transpose() * steady.cwiseQuotient(root_d_);
  const Eigen::VectorXd decayed = (-mode_rates_ * t).array().exp().matrix().cwiseProduct(in_modes);
  const double energy = root_d_(l) * modes_.row(l).dot(decayed);
  return 10.0 * std::log10(std::max(energy, 1e-300));
}

}  // namespace audio_propagation
