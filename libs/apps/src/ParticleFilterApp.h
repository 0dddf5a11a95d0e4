#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/bayes/CParticleFilterCapable.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/TMetricMapInitializer.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/EndsWith.h>

#include <memory>
#include <string>
#include <vector>

#include "SlamApp.h"

namespace mrpt_vslam::apps {

/** A driver app whose filter runs through MRPT's `CParticleFilter::executeOn()` (omni-fastslam,
 *  multirobot-vslam): the `[ParticleFilter]` options and their checks, the map every particle
 *  starts from, the filter with its particles and seed, and its steps. */
class ParticleFilterApp : public SlamApp {
  protected:
    ParticleFilterApp(core::AppArguments args, std::string name, std::string section);

    /// The most particles a run may ask for (each carries a map).
    static constexpr size_t kMaxParticles = 100000;
    /** Loads `[ParticleFilter]` into pf.m_options (core::loadParticleFilterOptions()). Throws a
     *  usage error naming the config for what that refuses, and unless 1 <= sampleSize <=
     *  kMaxParticles and, unless `adaptive`, adaptiveSampleSize is off. */
    /// \param adaptive whether the filter implements adaptiveSampleSize (KLD-sampling)
    void loadParticleFilterOptions(bool adaptive = false);

    /** `filter_runs` of the app's section (`runs` when absent): how many filters run side by
     *  side, from the seeds
     *  --seed, --seed + 1, ... (makeFilter()); after the run the one whose smoothed solution
     *  costs least is kept (keepCheapestRun()). Throws a usage error unless it is 1 to 64, and
     *  unless `smoothing` when it is more than 1 (`smoothingKey` names that switch). */
    size_t loadFilterRuns(size_t runs, bool smoothing, const std::string& smoothingKey) const;

    /// One of the filters run side by side, and the smoother that records its run.
    template <class FILTER, class SMOOTHER>
    struct TFilterRun {
        std::unique_ptr<FILTER> filter;
        std::unique_ptr<SMOOTHER> smoother;  ///< the filter's step observer
    };
    /// What the smoothing of one filter run gave, for run.json `results.filter_runs`.
    struct TRunOutcome {
        double cost = 0;                     ///< of its smoothed solution
        size_t landmarks = 0, readings = 0;  ///< of the smoothed map, and readings in it
    };
    /** Smooths every run (`smooth(run)`), keeps in `runs` only the one whose result costs least
     *  (`costOf(result)`; the first of equal ones) and stops stepping the filters. Returns
     *  every run's result, in the order of `runs`, and sets `kept` to the kept one's index. */
    template <class RUN, class SMOOTH, class COST>
    auto keepCheapestRun(std::vector<RUN>& runs, SMOOTH smooth, COST costOf, size_t& kept)
    {
        std::vector<decltype(smooth(runs.front()))> results;
        kept = 0;
        for (size_t i = 0; i < runs.size(); i++) {
            results.push_back(smooth(runs[i]));
            if (costOf(results[i]) < costOf(results[kept])) kept = i;
        }
        RUN run = std::move(runs[kept]);
        runs.clear();
        runs.push_back(std::move(run));
        stopStepping();
        return results;
    }
    /// run.json `results.filter_runs` (seed, cost, landmarks and readings of each run) and
    /// `counts.kept_seed`, when more than one filter ran.
    void reportFilterRuns(const std::vector<TRunOutcome>& outcomes, size_t kept,
                          core::RunReport& report) const;

    /// The map every particle starts from: the only map of `[MappingApplication]`, defined by
    /// `countKey` = 1.
    template <class MAP>
    MAP particleMapTemplate(const std::string& countKey) const
    {
        // Every particle's map comes from the .ini through MRPT's map registry. MRPT 2.5 leaks a
        // map definition whose loader throws, so ours is first loaded into one we own.
        const std::string exactlyOne =
            std::string("[") + kMapSection + "] must define exactly one map: " + countKey + " = 1";
        if (cfg.read_uint64_t(kMapSection, countKey, 0) != 1) throw usageError(exactlyOne);
        // other kinds of map, which MRPT would load unchecked (read from a copy, so that a
        // misspelt key is still reported as unknown)
        const mrpt::config::CConfigFileMemory text(cfg.effectiveText());
        std::vector<std::string> keys;
        text.getAllKeys(kMapSection, keys);
        for (const auto& key : keys) {
            const std::string k = mrpt::system::lowerCase(key);
            const bool count = core::endsWith(k, "_count");
            const std::string n = mrpt::system::trim(text.read_string(kMapSection, key, "0"));
            const bool positive = n.find_first_not_of("0123456789") == std::string::npos &&
                                  n.find_first_not_of('0') != std::string::npos;
            // (a count that is no number is left to the checked reader, which names the key)
            if (count && positive && !mrpt::system::strCmpI(key, countKey))
                throw usageError(exactlyOne);
            // MRPT reads a negative count as a huge one and defines maps without end
            if (count && !n.empty() && n.front() == '-')
                throw usageError(std::string("[") + kMapSection + "] " + key + " = " + n +
                                 ": a count of maps must be 0 or more");
        }
        mrpt::maps::TSetOfMetricMapInitializers inits;
        try {
            const std::string name = countKey.substr(0, countKey.rfind("_count"));
            typename MAP::TMapDefinition own;
            own.loadFromConfigFile(cfg, std::string(kMapSection) + "_" + name + "_00");
            inits.loadFromConfigFile(cfg, kMapSection);
        } catch (const std::exception& e) {
            throw configError(e);
        }
        mrpt::maps::CMultiMetricMap maps(inits);
        const auto map = maps.mapByClass<MAP>();
        if (!map || maps.maps.size() != 1) throw usageError(exactlyOne);
        return *map;
    }

    /// The filter over copies of `mapTemplate`, with sampleSize particles and the run's seed
    /// (plus `seedOffset`, for a filter run beside the first); filterStep() steps it until
    /// stopStepping().
    template <class FILTER, class MAP>
    std::unique_ptr<FILTER> makeFilter(const MAP& mapTemplate, uint32_t seedOffset = 0)
    {
        auto filter =
            std::make_unique<FILTER>(mapTemplate, pf.m_options.sampleSize, seed + seedOffset);
        filter->setThreadCount(args.threads);
        m_stepped.push_back({filter.get(), mrpt::random::CRandomGenerator(seed + seedOffset)});
        return filter;
    }

    /// One step of each filter of makeFilter(), in the order made, as one timedStep(); its
    /// errors name the rawlog and the step.
    void filterStep(const mrpt::obs::CActionCollection& actions,
                    const mrpt::obs::CSensoryFrame& frame, core::RunTimer& timer);
    /// filterStep() steps none of the filters made so far (they may be destroyed).
    void stopStepping() { m_stepped.clear(); }

    mrpt::bayes::CParticleFilter pf;  ///< options from `[ParticleFilter]`

  private:
    static constexpr const char* kMapSection = "MappingApplication";
    /// A filter filterStep() steps, and the state of the generator its resampling draws from:
    /// CParticleFilter's resampling draws from MRPT's global generator, so each filter's state
    /// is put there for its step and a filter run beside others draws as it would alone.
    struct TSteppedFilter {
        mrpt::bayes::CParticleFilterCapable* filter;
        mrpt::random::CRandomGenerator resampling;
    };
    std::vector<TSteppedFilter> m_stepped;
};

}  // namespace mrpt_vslam::apps
