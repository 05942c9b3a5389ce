"""help() in a notebook answers for every public name: each public function, class and
method has a docstring, and each argument whose name carries an SI unit (…_hz, …_s, …_v,
…_m, …_ohm, …_f, …_gb) is explained in its function's docstring with the unit in brackets."""
import inspect
import re

UNIT_SUFFIX = re.compile(r"_(hz|s|v|m|ohm|f|gb|c_per_m2)$")
UNITS = {"hz": "[Hz]", "s": "[s]", "v": "[V]", "m": "[m]", "ohm": "[Ohm]", "f": "[F]", "gb": "GB",
         "c_per_m2": "[C/m^2]"}


def public_callables(stengmc):
    for name in stengmc.__all__:
        value = getattr(stengmc, name)
        if inspect.isclass(value):
            yield name, value
            for member, attribute in vars(value).items():
                if not member.startswith("_") and (callable(attribute) or isinstance(attribute, property)):
                    yield f"{name}.{member}", attribute
        elif callable(value):
            yield name, value


def test_every_public_name_has_a_docstring(stengmc):
    missing = [name for name, value in public_callables(stengmc) if not (value.__doc__ or "").strip()]
    assert not missing, f"no docstring: {missing}"


def test_every_argument_with_a_unit_is_explained_with_it(stengmc):
    unexplained = []
    for name, value in public_callables(stengmc):
        if not inspect.isfunction(value):
            continue
        doc = value.__doc__ or ""
        for argument in inspect.signature(value).parameters:
            suffix = UNIT_SUFFIX.search(argument)
            if suffix and not (argument in doc and UNITS[suffix.group(1)] in doc):
                unexplained.append(f"{name}({argument})")
    assert not unexplained, f"arguments without their unit in the docstring: {unexplained}"
