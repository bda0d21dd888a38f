"""``betv schema [device|check]``: JSON schema of device files (pydantic ``DeviceSpec``) or
of ``betv check --json`` (:func:`betvdesign.checkview.check_json_schema`)."""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import typer

from betvdesign.cli import app
from betvdesign.cli.common import user_errors
from betvdesign.errors import UsageError
from betvdesign.spec import DeviceSpec


def device_schema() -> dict:
    """JSON schema of a device file (quantities are strings with units)."""
    schema = DeviceSpec.model_json_schema(mode="validation")
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "BETV device file (betvdesign)"
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
        from betvdesign.checkview import check_json_schema

        schema = check_json_schema()
    else:
        schema = device_schema()
    text = json.dumps(schema, indent=2, ensure_ascii=False) + "\n"
    if output is None:
        typer.echo(text, nl=False)
        return
    with user_errors():
        write_atomic(output, text)


def write_atomic(path: Path, text: str) -> None:
    """Write via a temporary file in the same directory and rename: never half a file."""
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.is_dir():
        raise UsageError(f"{path}: directory {directory} does not exist")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=directory)
    except OSError as exc:
        raise UsageError(f"{path}: cannot write: {exc.strerror}") from None
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        raise UsageError(f"{path}: cannot write: {exc.strerror}") from None
