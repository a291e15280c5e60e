// A cycle time a shop can trust: each block timed as the control moves it, with each axis's
// velocity and acceleration (the machine's [motion] table). A feed move speeds up and slows
// down along a trapezoidal velocity profile; it runs at its feed, or at what the slowest axis
// it moves allows; an arc no faster than its radius lets the axes turn the corner
// (v^2 <= a r); between two feed moves the tool slows for the corner by the junction-deviation
// rule (the speed at which the path may round the corner by at most `junction_deviation`); a
// planner looks 256 blocks ahead so every block can slow down in time. Rapids move each axis on
// its own, at its own top speed, from rest to rest. Rotaries bound a block's time by their
// degrees per second. Inverse-time blocks take at least their 1/F minutes.
//
// The simple estimate (length over feed) stays beside it as a lower bound.
#pragma once

#include <array>
#include <deque>

#include "readback/gcode_interp.h"
#include "machine/machine.h"

namespace clpc {

class MotionTimer {
 public:
  // With k.degrees_per_minute, F of a feed that turns a rotary is over all the axes at once
  // (the rotaries' travel as k's axes turn).
  explicit MotionTimer(const MotionSettings& m, const KinematicsSettings& k = {})
      : m_(m), kinematics_(k), dpm_(k.degrees_per_minute) {}
  bool known() const { return m_.known(); }
  // The next segment of the program, in order (machine axes, output units).
  void add(const gcode::Segment& s);
  // The machine stops (dwell, tool change, spindle, the end): what is planned is timed.
  void stop();
  double minutes();  // so far, the planned blocks stopped at the end

 private:
  struct Block {
    double length = 0;      // output units
    double v_max = 0;       // units per second: the feed, the axes, the arc's radius
    double accel = 0;       // units per second squared, along the path
    double v_corner = 0;    // the most it may enter with (the corner before it)
    double min_seconds = 0; // rotaries, inverse time
    ir::Vec3 dir_in = ir::Vec3::Zero(), dir_out = ir::Vec3::Zero();
  };
  void push(Block b);
  void plan(size_t retire);  // times the first `retire` blocks of the window
  static double trapezoid(double length, double v0, double v1, double v_max, double a);

  MotionSettings m_;
  KinematicsSettings kinematics_;
  bool dpm_ = false;
  std::deque<Block> window_;
  double entry_ = 0;  // the speed the first block of the window starts with (fixed)
  double seconds_ = 0;
};

}  // namespace clpc
