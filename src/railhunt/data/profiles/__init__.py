"""Shipped wheel and rail profiles (SIMPACK format): S1002 and UIC60 (60E1).

See README.md in this folder for their source and licence.
"""
