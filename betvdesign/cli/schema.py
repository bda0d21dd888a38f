"""``betv schema``: the JSON schema of device files (pydantic ``DeviceSpec``), with the
input limits of :mod:`betvdesign.limits` under ``x-betv-limits`` and in the description."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from betvdesign import limits
from betvdesign.cli import app
from betvdesign.cli.common import user_errors
from betvdesign.outputs import check_output_file, write_atomic
from betvdesign.spec import DeviceSpec


def device_schema() -> dict:
    """JSON schema of a device file (quantities are strings with units)."""
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


@app.command("schema")
def schema_cmd(
    output: Path | None = typer.Option(
        None, "-o", "--output", help="Write to this file (atomically) instead of stdout."
    ),
) -> None:
    """Print the JSON schema of device YAML files."""
    text = json.dumps(device_schema(), indent=2, ensure_ascii=False) + "\n"
    if output is None:
        typer.echo(text, nl=False)
        return
    with user_errors():
        write_atomic(check_output_file(output), text)
