#include "HapticDevice.h"

namespace thintissue
{

HapticDevice::~HapticDevice() = default;

} // namespace thintissue
