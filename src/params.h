#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace multirobot_audio {

// Thrown for a parameter that cannot be used; the message names the parameter and what was
// expected. Nodes print it and exit 1.
class ParamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The ParamError for an option of a ROS-free options struct that is named as its parameter:
// "<~field>: <problem>", where `field` may name an entry of a list ("microphones[2]").
ParamError OptionParamError(const ros::NodeHandle& pnh, const std::string& field, const std::string& problem);

// Runs `check`, a ROS-free options check that throws std::invalid_argument naming the field, so
// that the component's range is the one used: its error becomes the OptionParamError of the
// parameter among `fields` (each read into the option of that name) whose name its message
// holds first as a word, or of the one field given; else a ParamError of the node's namespace.
void CheckOptionParams(const ros::NodeHandle& pnh, const std::vector<std::string>& fields,
                       const std::function<void()>& check);

// Reads ~name (from `pnh`), or `fallback` when unset; throws ParamError on a value of the
// wrong type or outside [lo, hi].
double NumberParam(const ros::NodeHandle& pnh, const std::string& name, double fallback, double lo,
                   double hi);
int IntParam(const ros::NodeHandle& pnh, const std::string& name, int fallback, int lo, int hi);
// The same without a range, for options whose own check has it (a number may be NaN or
// infinite); the optional one is empty when unset.
double NumberParam(const ros::NodeHandle& pnh, const std::string& name, double fallback);
std::optional<double> OptionalNumberParam(const ros::NodeHandle& pnh, const std::string& name);
int IntParam(const ros::NodeHandle& pnh, const std::string& name, int fallback);
// A list of strings, empty when unset; throws ParamError "expected <expected>" for anything else.
std::vector<std::string> StringListParam(const ros::NodeHandle& pnh, const std::string& name,
                                         const std::string& expected);
std::string StringParam(const ros::NodeHandle& pnh, const std::string& name,
                        const std::string& fallback);
bool BoolParam(const ros::NodeHandle& pnh, const std::string& name, bool fallback);
// A number in (0, hi]: lengths, periods, rates.
double PositiveParam(const ros::NodeHandle& pnh, const std::string& name, double fallback,
                     double hi = 1e6);
// Throws when the parameter is unset or empty.
std::string RequiredStringParam(const ros::NodeHandle& pnh, const std::string& name);
// Throws when the parameter is unset, as IntParam does for a bad value.
int RequiredIntParam(const ros::NodeHandle& pnh, const std::string& name, int lo, int hi);
// A required, non-empty list of whole numbers in [lo, hi] (such as fiducial ids: [100, 101]);
// a single number is taken as a list of one. Throws when unset, empty, or of the wrong type.
std::vector<int> RequiredIntListParam(const ros::NodeHandle& pnh, const std::string& name, int lo,
                                      int hi);

}  // namespace multirobot_audio
