"""The command line's parser for the reference page (sphinx-argparse renders its help as
reStructuredText): blockdae's own parser, with the bars of plain-text help (peak |a|)
escaped so that they are not read as substitutions."""

import argparse

from blockdae.cli._main import _parser


def _escaped(text):
    return text.replace("|", r"\|") if isinstance(text, str) else text


def _escape(parser):
    parser.description = _escaped(parser.description)
    parser.epilog = _escaped(parser.epilog)
    for action in parser._actions:
        action.help = _escaped(action.help)
        if isinstance(action, argparse._SubParsersAction):
            for choice in action._choices_actions:
                choice.help = _escaped(choice.help)
            for sub in action.choices.values():
                _escape(sub)
    return parser


def parser():
    """blockdae's argparse parser, its help escaped for reStructuredText."""
    return _escape(_parser())
