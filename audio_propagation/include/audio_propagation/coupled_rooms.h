#pragma once

// Rooms coupled through their openings: how loud each room's reverberant field is when a source
// sounds in one of them, and how it dies away when the source stops. Each room holds a diffuse
// field of energy density E_i; it loses energy to its own surfaces (absorption A_i) and through
// every opening to a neighbour (area S_ij, which absorbs fully on both sides), and gains what
// comes back through the openings. In the steady state (Cremer and Mueller; Kuttruff, Room
// Acoustics, "coupled rooms"):
//   P_i = (c/4) [ (A_i + sum_j S_ij) E_i - sum_j S_ij E_j ],
// P_i the power of the sources in room i; after they stop, V_i dE_i/dt = -(that bracket), a sum
// of exponentials with one rate per room (two rooms: the double-slope decay).
//
// A_i is each room's own absorption, from its volume and its reverberation time with its openings
// shut, by Sabine's formula A = 24 ln(10) V / (c T60) (0.161 V / T60 at 343 m/s). A room with no
// openings is the single diffuse room the acoustic model has always had: its relative level is
// exactly 0 dB and its decay exactly its own RT60.
// No ROS.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace audio_propagation {

struct CoupledRoomSpec {
  std::string name;
  double volume = 0.0;  // m^3
  double rt60 = 0.0;    // s, openings shut
};

// An opening between rooms `a` and `b` (indices into the rooms) of `area` m^2: a doorway, an
// arch, the cross-section where a corridor meets a hall.
struct RoomOpening {
  std::size_t a = 0;
  std::size_t b = 0;
  double area = 0.0;
};

// Sabine's absorption (m^2) of a room of `volume` m^3 reverberating `rt60` s, and the speed of
// sound it is worked out with.
constexpr double kSoundSpeed = 343.0;  // m/s
double SabineAbsorption(double volume, double rt60);

class CoupledRooms {
 public:
  // Throws std::invalid_argument naming the room or opening and the field for no rooms, a
  // volume not above 0, an RT60 outside (0, 20] s, an opening joining a room to itself or to a
  // room that does not exist, or an area not above 0 (or not finite).
  CoupledRooms(std::vector<CoupledRoomSpec> rooms, std::vector<RoomOpening> openings);

  std::size_t size() const { return rooms_.size(); }
  const std::vector<CoupledRoomSpec>& rooms() const { return rooms_; }
  const std::vector<RoomOpening>& openings() const { return openings_; }
  double Absorption(std::size_t room) const { return absorption_[room]; }

  // The steady reverberant field in room `listener` from a source in room `source`, in dB
  // relative to the field the same source makes in its room with every opening shut
  // (4 W / (c A_source)): 10 log10(A_source [M^-1]_(listener, source)). 0 dB for a room with no
  // openings; below 0 in the source's own room (energy leaks out), and about 8 to 12 dB lower
  // per doorway passed between ordinary rooms. Rooms no chain of openings joins get
  // kNoCouplingDb.
  static constexpr double kNoCouplingDb = -200.0;
  double RelativeLevelDb(std::size_t source, std::size_t listener) const;

  // The reverberant energy in room `listener`, `t` s after a steady source in room `source`
  // stops, in dB relative to the steady field in the source's room shut (as RelativeLevelDb):
  // at t = 0 it is RelativeLevelDb, then it falls as a sum of exponentials, one per room.
  double DecayDb(std::size_t source, std::size_t listener, double t) const;

  // The energy decay rates (1/s) of the coupled rooms, slowest first: exp(-rate t) each. A room
  // alone decays at 6 ln(10) / RT60 (60 dB in RT60 s).
  const std::vector<double>& DecayRates() const { return rates_; }

 private:
  std::vector<CoupledRoomSpec> rooms_;
  std::vector<RoomOpening> openings_;
  std::vector<double> absorption_;
  Eigen::MatrixXd inverse_;   // M^-1, M = diag(A_i + sum_j S_ij) - S
  // The decay: E(t) = sqrt(D) Q exp(-Lambda t) Q^T sqrt(D)^-1 E(0), with D = diag(c / (4 V_i))
  // and Q Lambda Q^T = sqrt(D) M sqrt(D) (symmetric, so its rates are real and positive).
  Eigen::MatrixXd modes_;     // Q
  Eigen::VectorXd root_d_;    // sqrt(D)
  std::vector<double> rates_;           // Lambda, slowest first
  Eigen::VectorXd mode_rates_;          // Lambda in Q's column order
};

}  // namespace audio_propagation
