// Single-producer / single-consumer exchange of the latest value (a triple
// buffer): the producer fills back() and publish()es it; the consumer's
// latest() is the newest published value. Neither side locks, waits or
// allocates; a value is never read while it is written. Used between the
// physics thread and the 1 kHz servo loop (DESIGN.md: threads).
#ifndef LatestValue_h
#define LatestValue_h

#include <array>
#include <atomic>

namespace thintissue
{

template <typename T>
class LatestValue
{
public:
  LatestValue() = default;
  explicit LatestValue(const T& initial) { Buffers.fill(initial); }
  LatestValue(const LatestValue&) = delete;
  LatestValue& operator=(const LatestValue&) = delete;

  /// Producer: the buffer to fill before publish().
  T& back() { return Buffers[Back]; }
  /// Producer: makes back() the latest value; back() is another buffer now.
  void publish() { Back = Middle.exchange(Back | Fresh, std::memory_order_acq_rel) & Index; }

  /// Consumer: the latest published value (the initial one before any);
  /// stays valid and unchanged until the consumer's next call.
  const T& latest()
  {
    if (Middle.load(std::memory_order_acquire) & Fresh)
    {
      Front = Middle.exchange(Front, std::memory_order_acq_rel) & Index;
    }
    return Buffers[Front];
  }

private:
  static constexpr unsigned Fresh = 4;
  static constexpr unsigned Index = 3;
  std::array<T, 3> Buffers{};
  unsigned Back = 0;  ///< producer's
  unsigned Front = 1; ///< consumer's
  std::atomic<unsigned> Middle{ 2 };
};

} // namespace thintissue

#endif
