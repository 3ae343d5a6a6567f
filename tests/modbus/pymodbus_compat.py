# SPDX-License-Identifier: MIT
"""Import before pymodbus. Debian's python3-pymodbus 3.0 imports `serial_asyncio` at package import
time but only *recommends* python3-serial-asyncio; our tests use TCP only, so when that package
is absent a stand-in module that refuses serial use is registered instead."""
import sys
import types

try:
    import serial_asyncio  # noqa: F401
except ImportError:
    _m = types.ModuleType("serial_asyncio")

    async def create_serial_connection(*_args, **_kwargs):
        raise RuntimeError("serial transports need python3-serial-asyncio (apt install python3-serial-asyncio)")

    _m.create_serial_connection = create_serial_connection
    sys.modules["serial_asyncio"] = _m
