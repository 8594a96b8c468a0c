"""Vehicle layouts: bodies and force elements read from a file, assembled for the kernel.

Rooms: ``expressions`` (safe arithmetic of parameters), ``spec`` (the parsed layout),
``parse`` (the ``[[body]]``, ``[[element]]``, ``[wheel_rail]`` tables), ``params`` (the
``[parameters]`` table), ``assembly`` (one assembly of every layout into the kernel's
arrays), ``writer`` (a complete layout file from a vehicle).
"""
