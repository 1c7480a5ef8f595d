"""Numbers in case and study files read as YAML 1.2 reads them (YAML 1.2.2, section 10.3.2, the core schema).

PyYAML follows YAML 1.1, whose integers include octal with a bare leading zero (`040` is 32), sexagesimal
base 60 (`1:30` is 90) and binary (`0b101`), and whose floats need a dot (`1e-3` is a string). A case value
written `inlet_temperature: 040` must not become 32 degC. `Yaml12Loader` replaces PyYAML's int and float
resolvers and constructors by those of the YAML 1.2 core schema:

    int     [-+]?[0-9]+  (decimal, leading zeros allowed: 040 is 40)  |  0o[0-7]+  |  0x[0-9a-fA-F]+
    float   [-+]?(\\.[0-9]+|[0-9]+(\\.[0-9]*)?)([eE][-+]?[0-9]+)?  |  [-+]?\\.(inf|Inf|INF)  |  \\.(nan|NaN|NAN)

Anything else (`1:30`, `0b101`, `1_000`) is a string, which the case schema then refuses naming the key, the
value and the number it expected. Booleans and null keep PyYAML's resolvers.
"""

from __future__ import annotations

import math
import re

import yaml

INT = re.compile(r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+)$")
FLOAT = re.compile(r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
                   r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$")
_INT_TAG, _FLOAT_TAG = "tag:yaml.org,2002:int", "tag:yaml.org,2002:float"


class Yaml12Loader(yaml.SafeLoader):
    """PyYAML's safe loader with the integers and floats of the YAML 1.2 core schema (module docstring)."""

    def construct_yaml_int(self, node: yaml.ScalarNode) -> int:
        text = self.construct_scalar(node)
        if text.startswith("0o"):
            return int(text[2:], 8)
        if text.startswith("0x"):
            return int(text[2:], 16)
        return int(text, 10)

    def construct_yaml_float(self, node: yaml.ScalarNode) -> float:
        text = self.construct_scalar(node).lower()
        if text.endswith(".inf"):
            return -math.inf if text.startswith("-") else math.inf
        if text == ".nan":
            return math.nan
        return float(text)


Yaml12Loader.yaml_implicit_resolvers = {
    first: [(tag, regexp) for tag, regexp in resolvers if tag not in (_INT_TAG, _FLOAT_TAG)]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
Yaml12Loader.add_implicit_resolver(_INT_TAG, INT, list("-+0123456789"))  # before the float: '40' is an int
Yaml12Loader.add_implicit_resolver(_FLOAT_TAG, FLOAT, list("-+0123456789."))
Yaml12Loader.add_constructor(_INT_TAG, Yaml12Loader.construct_yaml_int)
Yaml12Loader.add_constructor(_FLOAT_TAG, Yaml12Loader.construct_yaml_float)
