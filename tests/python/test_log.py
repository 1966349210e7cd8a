# tacta.set_log_handler / set_log_level: the engine's one message sink from Python (the sink
# itself, levels and the stderr default, is tested in tests/engine/log).
import logging

import pytest
import tacta


def test_a_logger_can_take_the_messages_and_none_gives_them_back():
    logger = logging.getLogger("tacta")
    tacta.set_log_handler(logger.log)
    tacta.set_log_level("debug")
    tacta.set_log_level("info")
    tacta.set_log_handler(None)


def test_an_unknown_level_is_refused_with_the_names_it_takes():
    with pytest.raises(ValueError, match="'debug', 'info', 'warning', 'error' or 'off', found 'loud'"):
        tacta.set_log_level("loud")
