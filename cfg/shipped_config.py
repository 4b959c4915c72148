"""The shipped config's values: the live parameters' defaults and ranges start from them (one place
for each default: config/semantic_edge_vo.yaml, which equals the built-in defaults)."""
import os

import yaml

_CONFIG = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "config", "semantic_edge_vo.yaml")
with open(_CONFIG) as _file:
    _VALUES = yaml.safe_load(_file)


def shipped(nodelet, key):
    """The value of `key` ("a/b" for nested blocks) in `nodelet`'s block."""
    value = _VALUES[nodelet]
    for part in key.split("/"):
        value = value[part]
    return value
