#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>
#include <mrpt_vslam/test/SyntheticTeamWorld.h>

#include <algorithm>
#include <bitset>
#include <map>
#include <utility>

using namespace mrpt_vslam::multirobot;
using mrpt_vslam::test::positionError;
using mrpt_vslam::test::standardFilter;
using mrpt_vslam::test::SyntheticTeamWorld;

TEST(CMultiRobotVisualSLAM, TeamWeightIsTheProductOverRobotsAndMeasurements)
{
    SyntheticTeamWorld::TParams wp;
    wp.landmarks = 300;
    SyntheticTeamWorld world(wp);
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 5, 3);
    filter.options.max_observations_per_robot = 6;
    filter.reset(world.startPoses(), world.time);
    auto pf = standardFilter();
    pf.m_options.BETA = 0;  // never resample: compare particle by particle
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
    for (int i = 0; i < 3; i++) {
        world.step(acts, sf);
        pf.executeOn(filter, &acts, &sf);
    }
    // replay the next step on copies of the maps, with the poses the filter sampled
    world.step(acts, sf);
    std::vector<CVisualLandmarksMap> before;
    std::vector<double> acc_before;
    for (size_t i = 0; i < filter.particlesCount(); i++) {
        before.push_back(filter.m_particles[i].d->map);
        acc_before.push_back(filter.m_particles[i].d->accumulated_log_w);
    }
    pf.executeOn(filter, &acts, &sf);
    ASSERT_GT(filter.lastStepStats.associated, 0u);
    double total_expected = 0;
    for (size_t i = 0; i < filter.particlesCount(); i++) {
        const auto& p = *filter.m_particles[i].d;
        double expected = 0;
        for (size_t k = 0; k < 2; k++) {
            auto obs =
                sf.getObservationBySensorLabelAs<mrpt::obs::CObservationVisualLandmarks::Ptr>(
                    "R" + std::to_string(k + 1) + "_LANDMARKS");
            for (const auto& m : selectNearest(measurementsFromObservation(*obs), 6)) {
                const auto in_map = toMapFrame(m, p.poses[k]);
                // wide search: the result must not depend on the filter's spread radius
                auto candidates = before[i].findCandidates(m, in_map, 10);
                expected += before[i].fuse(m, in_map, candidates, static_cast<unsigned>(k)).log_w;
            }
        }
        EXPECT_NEAR(p.accumulated_log_w - acc_before[i], expected, 1e-6) << "particle " << i;
        total_expected += expected;
    }
    EXPECT_TRUE(std::isfinite(total_expected));
}

// resample_per_robot: with BETA above 1 the particles are resampled after robot 1's
// measurements, which resets the weights; robot 2 measures nothing in this step, so every
// weight must be back to 0. Without the option robot 1's weights remain and differ.
TEST(CMultiRobotVisualSLAM, ResamplingAfterEachRobotResetsWeightsBetweenRobots)
{
    for (const bool per_robot : {true, false}) {
        SyntheticTeamWorld::TParams wp;
        wp.landmarks = 300;
        SyntheticTeamWorld world(wp);
        CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 50, 5);
        mrpt::random::getRandomGenerator().randomize(5);
        filter.options.resample_per_robot = per_robot;
        filter.reset(world.startPoses(), world.time);
        auto pf = standardFilter();
        mrpt::obs::CActionCollection acts;
        mrpt::obs::CSensoryFrame sf;
        for (int i = 0; i < 3; i++) {
            world.step(acts, sf);
            pf.executeOn(filter, &acts, &sf);
        }
        world.step(acts, sf);
        mrpt::obs::CSensoryFrame only_r1;
        only_r1.insert(sf.getObservationBySensorLabel("R1_LANDMARKS"));
        pf.m_options.BETA = 2;  // always resample when asked
        for (auto& p : filter.m_particles) p.log_w = 0;
        filter.prediction_and_update(&acts, &only_r1, pf.m_options);  // no final resampling
        ASSERT_GT(filter.lastStepStats.measurements, 0u);
        double min_w = 1e300, max_w = -1e300;
        for (const auto& p : filter.m_particles) {
            min_w = std::min(min_w, p.log_w);
            max_w = std::max(max_w, p.log_w);
        }
        if (per_robot) {
            EXPECT_EQ(min_w, 0.0);
            EXPECT_EQ(max_w, 0.0);
        } else {
            EXPECT_GT(max_w - min_w, 1.0) << "robot 1's weights must still differ";
        }
    }
}

// Resampling takes the landmarks of the particles that died out of the pool's search: after a
// resampling onto one particle, the search finds that particle's landmarks and no other.
TEST(CMultiRobotVisualSLAM, ResamplingLeavesOnlyHeldLandmarksInThePoolsSearch)
{
    SyntheticTeamWorld::TParams wp;
    wp.landmarks = 300;
    SyntheticTeamWorld world(wp);
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 20, 7);
    filter.reset(world.startPoses(), world.time);
    auto pf = standardFilter();
    pf.m_options.BETA = 0;  // never resample
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
    for (int i = 0; i < 6; i++) {
        world.step(acts, sf);
        pf.executeOn(filter, &acts, &sf);
    }
    const auto searchable = [&] {
        const auto& pool = filter.m_particles[0].d->map.descriptorPool();
        std::vector<TLandmarkCandidate> all;
        pool.findCandidates(Eigen::Vector3d::Zero(), 1e6, pool.descriptor(0), 1e9, all);
        std::vector<uint32_t> ids;
        for (const auto& c : all) ids.push_back(c.id);
        std::sort(ids.begin(), ids.end());
        return ids;
    };
    const size_t pool_size = filter.m_particles[0].d->map.descriptorPool().size();
    ASSERT_EQ(searchable().size(), pool_size);
    // particle 3 alone loses its landmarks seen fewer than 3 times
    ASSERT_GT(filter.m_particles[3].d->map.removeLandmarksSeenLessThan(3), 0u);
    filter.performSubstitution(std::vector<size_t>(filter.particlesCount(), 3));
    std::vector<uint32_t> held;
    filter.m_particles[0].d->map.landmarks().forEach(
        [&](uint32_t id, const TVisualLandmark&) { held.push_back(id); });
    EXPECT_EQ(searchable(), held);
    EXPECT_LT(held.size(), pool_size);
    EXPECT_GE(pool_size, 32u) << "too few landmarks for the search to be pruned";
}

// Each step of a path holds its correspondences, which resampling (here after every robot)
// carries with the map they were fused into: a particle's history has one entry per fusion into
// its map, by the robot that made it. The step observer hears of every robot of every step.
TEST(CMultiRobotVisualSLAM, PathStepsHoldTheCorrespondencesOfTheParticlesMap)
{
    struct TRecorder : CMultiRobotVisualSLAM::TStepObserver {
        std::vector<std::pair<size_t, size_t>> steps;  // (step, robot)
        size_t measurements = 0, resets = 0;
        void onReset(const std::vector<mrpt::math::TPose2D>& start, double, double) override
        {
            resets++;
            EXPECT_EQ(start.size(), 2u);
        }
        void onRobotStep(size_t step, size_t robot, const mrpt_vslam::core::TOdometryGaussian&,
                         const std::vector<TLandmarkMeasurement>& z,
                         const std::vector<CMultiRobotVisualSLAM::TRobotReading>&) override
        {
            steps.emplace_back(step, robot);
            measurements += z.size();
        }
    };
    for (const bool optimal : {false, true}) {
        SCOPED_TRACE(optimal ? "optimal proposal" : "standard proposal");
        SyntheticTeamWorld::TParams wp;
        wp.landmarks = 300;
        SyntheticTeamWorld world(wp);
        CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 20, 3);
        mrpt::random::getRandomGenerator().randomize(3);
        filter.options.resample_per_robot = true;
        TRecorder recorder;
        filter.setStepObserver(&recorder);
        filter.reset(world.startPoses(), world.time);
        auto pf = standardFilter();
        if (optimal) pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfOptimalProposal;
        pf.m_options.BETA = 2;  // always resample when asked
        mrpt::obs::CActionCollection acts;
        mrpt::obs::CSensoryFrame sf;
        size_t measurements = 0;
        for (int i = 0; i < 10; i++) {
            world.step(acts, sf);
            pf.executeOn(filter, &acts, &sf);
            measurements += filter.lastStepStats.measurements;
        }
        EXPECT_EQ(recorder.resets, 1u);
        ASSERT_EQ(recorder.steps.size(), 20u);
        for (size_t i = 0; i < recorder.steps.size(); i++)
            EXPECT_EQ(recorder.steps[i], std::make_pair(i / 2 + 1, i % 2)) << i;
        EXPECT_EQ(recorder.measurements, measurements);
        for (const auto& particle : filter.m_particles) {
            const TTeamParticle& p = *particle.d;
            std::map<uint32_t, std::pair<uint32_t, uint32_t>> fused;  // times, robot bits
            const auto history = TLandmarkIdentityTally::historyOf(p);
            for (const auto& c : history) {
                fused[c.landmark].first++;
                fused[c.landmark].second |= 1u << c.robot;
            }
            ASSERT_EQ(fused.size(), p.map.size());
            p.map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
                EXPECT_EQ(fused[id].first, lm.times_seen) << id;
                EXPECT_EQ(fused[id].second, lm.seen_by) << id;
            });
            // the world's points carry their index as track_id: each landmark has an identity
            EXPECT_EQ(TLandmarkIdentityTally::of(history, p.map).landmarks_with_identity,
                      p.map.size());
        }
    }
}

// A robot whose step action stands still (no reading since the last step, in a live team) and
// that has nothing to fuse keeps every particle's pose exactly; the same steps as noisy zero
// increments spread them.
TEST(CMultiRobotVisualSLAM, ARobotThatStandsStillWithoutReadingsKeepsItsPoses)
{
    for (const bool still : {true, false}) {
        SCOPED_TRACE(still ? "standing still" : "zero increments");
        SyntheticTeamWorld world(SyntheticTeamWorld::TParams{});
        CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 20, 5);
        filter.options.initial_std_xy = filter.options.initial_std_phi = 0;
        filter.reset(world.startPoses(), world.time);
        auto pf = standardFilter();
        mrpt::obs::CActionCollection acts, team_acts;
        mrpt::obs::CSensoryFrame sf, r1_only;
        for (int i = 0; i < 5; i++) {
            world.step(acts, sf);
            team_acts.clear();
            team_acts.insert(*acts.get(0));
            mrpt::obs::CActionRobotMovement2D r2;
            if (still)
                r2.poseChange = mrpt::poses::CPosePDFGaussian::Create();
            else
                r2.computeFromOdometry(mrpt::poses::CPose2D(),
                                       mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
            team_acts.insert(r2);
            r1_only.clear();
            r1_only.insert(sf.getObservationByIndex(0));
            pf.executeOn(filter, &team_acts, &r1_only);
        }
        const auto start = world.startPoses();
        size_t r1_moved = 0, r2_moved = 0;
        for (const auto& particle : filter.m_particles) {
            r1_moved += !(particle.d->poses[0] == start[0]);
            r2_moved += !(particle.d->poses[1] == start[1]);
        }
        EXPECT_EQ(r1_moved, filter.m_particles.size());
        EXPECT_EQ(r2_moved, still ? 0u : filter.m_particles.size());
        EXPECT_EQ(CMultiRobotVisualSLAM::pathOf(*filter.m_particles[0].d, 1).size(), 6u);
    }
}

TEST(CMultiRobotVisualSLAM, TwoRobotsBeatOdometryAndMergeSharedLandmarks)
{
    SyntheticTeamWorld::TParams wp;
    wp.landmarks = 500;
    wp.seed = 7;
    SyntheticTeamWorld world(wp);
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 500, 11);
    mrpt::random::getRandomGenerator().randomize(11);
    filter.options.max_observations_per_robot = 8;
    filter.reset(world.startPoses(), world.time);
    auto pf = standardFilter();
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
    const int steps = 140;  // two laps of 13.8 m circles, M = 500 as the paper online
    std::vector<std::vector<mrpt::math::TPose2D>> truth(2), odo(2);
    for (int i = 0; i < steps; i++) {
        world.step(acts, sf);
        pf.executeOn(filter, &acts, &sf);
        for (size_t k = 0; k < 2; k++) {
            truth[k].push_back(world.truth[k]);
            odo[k].push_back(world.odometry[k]);
        }
    }
    const auto& best = filter.bestParticle();
    for (size_t k = 0; k < 2; k++) {
        const auto path = CMultiRobotVisualSLAM::pathOf(best, k);
        ASSERT_EQ(path.size(), static_cast<size_t>(steps + 1));
        double se = 0, se_odo = 0;
        for (int i = 0; i < steps; i++) {
            se += std::pow(positionError(path[i + 1].second, truth[k][i]), 2);
            se_odo += std::pow(positionError(odo[k][i], truth[k][i]), 2);
        }
        const double rmse = std::sqrt(se / steps), rmse_odo = std::sqrt(se_odo / steps);
        EXPECT_LT(rmse, 0.25) << "robot " << k;
        EXPECT_LT(rmse, 0.5 * rmse_odo) << "robot " << k << " odometry " << rmse_odo;
    }
    // landmarks against the true points (identified by their descriptors): a point both
    // robots measured must be one landmark
    size_t merged = 0, duplicated = 0, far = 0;
    std::vector<int> hits(world.points.size(), 0);
    best.map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        const size_t i = world.pointOfDescriptor(best.map.descriptorPool().descriptor(id));
        hits[i]++;
        if ((world.points[i] - lm.mean).norm() > 0.3) far++;
        if (std::bitset<32>(lm.seen_by).count() == 2) merged++;
    });
    for (int h : hits) duplicated += h > 1 ? 1 : 0;
    EXPECT_GT(merged, 20u) << "landmarks both robots measured";
    EXPECT_LT(duplicated, merged / 10 + 2);
    EXPECT_LT(far, best.map.size() / 10);
}
