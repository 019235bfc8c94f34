"""MkDocs hook: the model-file reference pages are generated from the model schema when the site
is built (drivedyn.front.schema.reference_markdown), so they cannot drift from what the loader accepts."""
import re


def on_page_markdown(markdown, page, config, files):
    from drivedyn.front.schema import reference_markdown

    return re.sub(r"<!-- model-reference: ([a-z-]+) -->", lambda m: reference_markdown(m.group(1)), markdown)
