"""The front: what a user reads and types. The command line (cli.py), the report page
(report.py, templates/), check's overview tables (overview.py) and the model files' JSON Schema
(schema.py). Thin: each command calls one public function of the API (drivedyn/api.py)."""
