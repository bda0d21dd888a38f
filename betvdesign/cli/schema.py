"""``betv schema [device|check]``: JSON schema of device files (pydantic ``DeviceSpec``, with
the input limits of :mod:`betvdesign.spec.limits` under ``x-betv-limits`` and in the
description) or of ``betv check --json`` (:func:`betvdesign.checks.view.check_json_schema`)."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from betvdesign.cli import app
from betvdesign.cli.common import user_errors
from betvdesign.errors import UsageError
from betvdesign.output.files import check_output_file, write_atomic
from betvdesign.spec import limits


def device_schema() -> dict:
    """JSON schema of a device file (quantities are strings with units)."""
    from betvdesign.spec.fielddocs import describe_fields
    from betvdesign.spec.models import DeviceSpec  # loaded on use: `betv --help` stays light

    describe_fields(DeviceSpec)
    schema = DeviceSpec.model_json_schema(mode="validation")
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "BETV device file (betvdesign)"
    schema["x-betv-limits"] = limits.describe()
    schema["description"] = (
        (schema.get("description") or "").rstrip()
        + "\n\nInput limits (refused with exit 2, naming the field and the limit): "
        + "; ".join(f"{k} {v['value']} ({v['what']})" for k, v in limits.describe().items())
    ).strip()
    return schema


SCHEMAS = ("device", "check")


@app.command("schema")
def schema_cmd(
    kind: str = typer.Argument(
        "device",
        metavar="[device|check]",
        help="device: device YAML files; check: the output of `betv check --json`.",
    ),
    output: Path | None = typer.Option(
        None, "-o", "--output", help="Write to this file (atomically) instead of stdout."
    ),
) -> None:
    """Print a JSON schema: of device YAML files (default) or of `betv check --json`."""
    with user_errors():
        if kind.lower() not in SCHEMAS:
            raise UsageError(f"unknown schema {kind!r}: use {' or '.join(SCHEMAS)}")
    if kind.lower() == "check":
        from betvdesign.checks.view import check_json_schema

        schema = check_json_schema()
    else:
        schema = device_schema()
    text = json.dumps(schema, indent=2, ensure_ascii=False) + "\n"
    if output is None:
        typer.echo(text, nl=False)
        return
    with user_errors():
        write_atomic(check_output_file(output), text)
