#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/team/TeamMessage.h>

#include <chrono>
#include <stdexcept>

namespace mrpt_vslam::team {
namespace {
/// Tells a message of this layout from other bytes and from other versions.
constexpr uint32_t kMagic = 0x56534c31;  // "VSL1"
/// Ends a message: a short read of a field (which MRPT's archives let pass) shows in it.
constexpr uint32_t kEnd = 0x454e4421;  // "END!"
}  // namespace

std::vector<uint8_t> TTeamMessage::encode() const
{
    mrpt::io::CMemoryStream buffer;
    auto out = mrpt::serialization::archiveFrom(buffer);
    out << kMagic << static_cast<uint8_t>(type) << robot << seq
        << static_cast<int64_t>(data_time.time_since_epoch().count()) << sent_time
        << static_cast<int64_t>(watermark.time_since_epoch().count());
    const bool hasObservation = type == Type::Reading;
    if (hasObservation) {
        if (!observation) throw std::logic_error("a Reading message needs an observation");
        out.WriteObject(observation.get());
    }
    out << kEnd;
    const auto* bytes = static_cast<const uint8_t*>(buffer.getRawBufferData());
    return std::vector<uint8_t>(bytes, bytes + buffer.getTotalBytesCount());
}

TTeamMessage TTeamMessage::decode(const void* data, size_t size)
{
    mrpt::io::CMemoryStream buffer;
    buffer.assignMemoryNotOwn(data, size);
    auto in = mrpt::serialization::archiveFrom(buffer);
    TTeamMessage m;
    try {
        uint32_t magic = 0;
        uint8_t type = 0;
        in >> magic;
        if (magic != kMagic) throw std::runtime_error("not a message of this version");
        int64_t dataTicks = 0, watermarkTicks = 0;
        in >> type >> m.robot >> m.seq >> dataTicks >> m.sent_time >> watermarkTicks;
        m.data_time = mrpt::Clock::time_point(mrpt::Clock::duration(dataTicks));
        m.watermark = mrpt::Clock::time_point(mrpt::Clock::duration(watermarkTicks));
        if (type < static_cast<uint8_t>(Type::Hello) || type > static_cast<uint8_t>(Type::Done))
            throw std::runtime_error("unknown message type " + std::to_string(type));
        m.type = static_cast<Type>(type);
        if (m.type == Type::Reading) {
            m.observation = std::dynamic_pointer_cast<mrpt::obs::CObservation>(in.ReadObject());
            if (!m.observation) throw std::runtime_error("a reading holds no observation");
        }
        uint32_t end = 0;
        in >> end;
        if (end != kEnd) throw std::runtime_error("truncated");
    } catch (const std::exception& e) {
        throw std::runtime_error(std::string("bad team message: ") + e.what());
    }
    if (buffer.getPosition() != size) throw std::runtime_error("bad team message: extra bytes");
    return m;
}

double wallClockNow()
{
    using namespace std::chrono;
    return duration<double>(system_clock::now().time_since_epoch()).count();
}

}  // namespace mrpt_vslam::team
