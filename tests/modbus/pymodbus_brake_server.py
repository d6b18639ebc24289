#!/usr/bin/python3
"""An independent Modbus TCP server (pymodbus) holding the default brake register map of
bench.md §3 with fixed readback values, for the client's peer test.

Usage: pymodbus_brake_server.py PORT
"""
import struct
import sys

from pymodbus.datastore import (ModbusSequentialDataBlock, ModbusServerContext,
                                ModbusSlaveContext)
from pymodbus.server import StartTcpServer


def float_words(value):
    hi, lo = struct.unpack(">HH", struct.pack(">f", value))  # ABCD: high word first
    return [hi, lo]


def main():
    port = int(sys.argv[1])
    inputs = [0] * 32
    inputs[0] = 0b100011  # output on, alarm, at setpoint
    inputs[10:12] = float_words(1.25)   # coil current, A
    inputs[12:14] = float_words(62.5)   # torque, N·m
    inputs[14:16] = float_words(81.5)   # coil temperature, °C
    inputs[16:18] = float_words(12.0)   # slip power, W
    inputs[20] = 1                      # alarm code: over-temperature
    inputs[0] |= 1 << 2
    store = ModbusSlaveContext(
        di=ModbusSequentialDataBlock(0, [0] * 32),
        co=ModbusSequentialDataBlock(0, [0] * 32),
        hr=ModbusSequentialDataBlock(0, [0] * 32),
        ir=ModbusSequentialDataBlock(0, inputs),
        zero_mode=True)
    context = ModbusServerContext(slaves={1: store}, single=False)
    StartTcpServer(context=context, address=("127.0.0.1", port))


if __name__ == "__main__":
    main()
