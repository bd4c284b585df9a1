"""scripts/measure-estimator.py's run configuration: the shipped estimator configuration with the
run's mode and the --set settings, estimator options in its `estimator:` section and
`segmenter.KEY` options in a `segmenter:` section after it."""

import importlib.util

import pytest

from conftest import SOURCE_DIR

SCRIPT = SOURCE_DIR / "scripts" / "measure-estimator.py"


def load_script():
    spec = importlib.util.spec_from_file_location("measure_estimator", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


SHIPPED = "estimator:\n  max_range_m: 12\n"


def test_estimator_settings_go_into_the_estimator_section():
    text = load_script().config_text(SHIPPED, "ml_ransac",
                                     ["gate_d1_chi2=9.21", "estimator.seed=3"])
    assert text == ("estimator:\n  max_range_m: 12\n  mode: ml_ransac\n  gate_d1_chi2: 9.21\n"
                    "  seed: 3\n")


def test_segmenter_settings_go_into_a_segmenter_section_after_it():
    text = load_script().config_text(
        SHIPPED, "static_nn",
        ["segmenter.person_separate_dropout_pieces=true", "seed=2"])
    assert text == ("estimator:\n  max_range_m: 12\n  mode: static_nn\n  seed: 2\n"
                    "segmenter:\n  person_separate_dropout_pieces: true\n")


def test_another_section_is_a_one_line_error():
    with pytest.raises(SystemExit) as error:
        load_script().config_text(SHIPPED, "ml_ransac", ["world.seed=1"])
    assert "only estimator and segmenter options" in str(error.value)
