#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt_vslam/core/RawlogEntrySource.h>

#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** Which observations an app takes as its input: those of one class (or derived from it) and,
 *  when `label` is not empty, with that sensor label. An empty label takes every observation of
 *  the class: in a rawlog a label is a filter, not a requirement.
 *
 *  Usage: `const auto sel = ObservationSelector::of<CObservationImage>(cfgLabel);` then
 *  `sel.matches(*obs)`, or `ObservationSelector::allIn<CObservationImage>(frame, cfgLabel)`. */
struct ObservationSelector {
    const mrpt::rtti::TRuntimeClassId* cls = nullptr;
    std::string label;
    /** Not empty: the run reads one sensor's observations of the class (one camera model, one
     *  sensor pose), so with an empty `label` they must all carry one label; the config key
     *  that names it, for messages (ActionFrameSource checks). */
    std::string one_sensor_key;

    template <class T>
    static ObservationSelector of(const std::string& label)
    {
        return {CLASS_ID(T), label, {}};
    }

    /// of(), for a class the run reads from one sensor, named by the config key `key`.
    template <class T>
    static ObservationSelector ofOneSensor(const std::string& label, const std::string& key)
    {
        return {CLASS_ID(T), label, key};
    }

    bool matches(const mrpt::obs::CObservation& obs) const
    {
        return obs.GetRuntimeClass()->derivedFrom(cls) &&
               (label.empty() || obs.sensorLabel == label);
    }

    /// For messages: the class name, and the label when there is one
    /// ("CObservationImage", "CObservationImage labelled 'CAMERA'").
    std::string describe() const { return shortClassName(*cls) + labelled(label); }

    /// For messages: " labelled 'LABEL'", or nothing for an empty label (any label).
    static std::string labelled(const std::string& label)
    {
        return label.empty() ? "" : " labelled '" + label + "'";
    }

    /// For messages: an observation's sensor label, or its class name when it has none.
    static std::string nameOf(const mrpt::obs::CObservation& obs)
    {
        return obs.sensorLabel.empty() ? shortClassName(obs) : obs.sensorLabel;
    }

    /// Removes the observations of `frame` that match; returns how many.
    size_t eraseFrom(mrpt::obs::CSensoryFrame& frame) const
    {
        size_t erased = 0;
        for (auto it = frame.begin(); it != frame.end();) {
            if (*it && matches(**it)) {
                it = frame.erase(it);
                erased++;
            } else {
                ++it;
            }
        }
        return erased;
    }

    /// The observations of `frame` of class T with sensor label `label` (any label if empty).
    template <class T>
    static std::vector<typename T::Ptr> allIn(const mrpt::obs::CSensoryFrame& frame,
                                              const std::string& label)
    {
        std::vector<typename T::Ptr> found;
        const auto sel = of<T>(label);
        for (const auto& obs : frame)
            if (obs && sel.matches(*obs)) found.push_back(std::dynamic_pointer_cast<T>(obs));
        return found;
    }

    /// The first of allIn(), or null.
    template <class T>
    static typename T::Ptr firstIn(const mrpt::obs::CSensoryFrame& frame, const std::string& label)
    {
        const auto sel = of<T>(label);
        for (const auto& obs : frame)
            if (obs && sel.matches(*obs)) return std::dynamic_pointer_cast<T>(obs);
        return {};
    }
};

}  // namespace mrpt_vslam::core
