"""The add-on as a user meets it: installed from the zip into a fresh profile, baking real probes through every
kind of world, re-baking, restoring, undoing, and refusing bad worlds with a one-line report. One Blender runs every
subject (tests/blender/addon/: baking, worlds, lamps, render settings, memory, installing), the add-on installed
once (addon_common.py)."""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "addon"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))  # rgbe.py
import harness  # noqa: E402
import addon_common  # noqa: E402,F401  (installs the add-on before the subjects load)
from addon_bake import (  # noqa: E402
    test_register_unregister,
    test_real_probes_bake_with_their_energy,
    test_every_method_bakes,
    test_auto_fits_both_cuts_up_to_16_lights,
    test_estimated_errors_and_count_by_tolerance,
    test_more_suns_than_pay_off_are_reported_with_this_versions_measurements,
    test_the_default_count_follows_the_engine,
    test_tradeoff_in_the_panel,
    test_tolerance_never_backfires,
    test_bad_worlds_are_one_line_reports,
    test_inputs_that_are_not_what_they_claim)
from addon_worlds import (  # noqa: E402
    test_strength_and_rotation_carry_into_the_lights,
    test_node_group_and_reroute,
    test_mirror_ball_image,
    test_sky_texture_world_is_rendered,
    test_read_and_rendered_worlds_agree,
    test_plain_colour_world_and_its_restore,
    test_restore_brings_the_world_back_exactly)
from addon_lamps import (  # noqa: E402
    test_rebake_replaces_only_its_own_lights,
    test_lamps_light_the_effects_of_their_split_and_sample_by_importance_only_with_reflections,
    test_point_lights_give_the_same_irradiance_at_the_origin,
    test_lamps_follow_the_worlds_rotation_and_strength,
    test_suns_on_a_dome_around_the_scene_under_one_rig,
    test_worlds_keep_their_own_lamps_and_mix,
    test_a_bake_by_version_0_1_is_adopted,
    test_lamps_of_an_earlier_bake_light_every_effect_in_eevee,
    test_the_bakes_nodes_are_framed_beside_the_users,
    test_thousands_of_lamps_go_in_one_batch)
from addon_render_settings import (  # noqa: E402
    test_cycles_settings_offer_and_restore,
    test_eevee_shadow_pool_follows_the_scene_and_restore,
    test_eevee_ray_tracing_offered_for_the_lamps_bounce_and_restore,
    test_a_light_probe_sphere_only_where_something_reflects,
    test_light_probes_baked_here_are_flagged_when_the_lamps_or_objects_change)
from addon_memory import (  # noqa: E402
    test_the_read_buffer_is_reused_only_when_nobody_holds_it,
    test_the_cores_table_buffers_are_given_back_a_minute_after_the_last_bake)
from addon_animation import (  # noqa: E402
    test_an_image_sequence_bakes_into_keyed_lamps_that_keep_their_ids,
    test_a_bake_of_an_image_sequence_reads_the_scenes_frame_and_restore_takes_the_keys,
    test_sequence_frames_are_the_ones_cycles_renders,
    test_an_animated_sky_is_rendered_frame_by_frame,
    test_the_tradeoff_says_what_bake_animation_costs)
from addon_install import (  # noqa: E402
    test_another_platforms_zip_is_refused_and_the_installed_one_kept,
    test_panel_draws_at_default_width_in_this_blender)

harness.run([test_register_unregister, test_real_probes_bake_with_their_energy,
             test_strength_and_rotation_carry_into_the_lights, test_every_method_bakes,
             test_auto_fits_both_cuts_up_to_16_lights,
             test_estimated_errors_and_count_by_tolerance,
             test_more_suns_than_pay_off_are_reported_with_this_versions_measurements,
             test_the_default_count_follows_the_engine, test_tradeoff_in_the_panel, test_node_group_and_reroute, test_mirror_ball_image,
             test_sky_texture_world_is_rendered, test_read_and_rendered_worlds_agree,
             test_plain_colour_world_and_its_restore,
             test_rebake_replaces_only_its_own_lights, test_restore_brings_the_world_back_exactly,
             test_lamps_light_the_effects_of_their_split_and_sample_by_importance_only_with_reflections,
             test_bad_worlds_are_one_line_reports,
             test_point_lights_give_the_same_irradiance_at_the_origin,
             test_lamps_follow_the_worlds_rotation_and_strength, test_suns_on_a_dome_around_the_scene_under_one_rig,
             test_worlds_keep_their_own_lamps_and_mix, test_a_bake_by_version_0_1_is_adopted,
             test_lamps_of_an_earlier_bake_light_every_effect_in_eevee,
             test_the_bakes_nodes_are_framed_beside_the_users,
             test_tolerance_never_backfires, test_cycles_settings_offer_and_restore,
             test_eevee_shadow_pool_follows_the_scene_and_restore,
             test_eevee_ray_tracing_offered_for_the_lamps_bounce_and_restore,
             test_a_light_probe_sphere_only_where_something_reflects,
             test_light_probes_baked_here_are_flagged_when_the_lamps_or_objects_change,
             test_the_read_buffer_is_reused_only_when_nobody_holds_it,
             test_the_cores_table_buffers_are_given_back_a_minute_after_the_last_bake,
             test_inputs_that_are_not_what_they_claim, test_thousands_of_lamps_go_in_one_batch,
             test_panel_draws_at_default_width_in_this_blender,
             test_an_image_sequence_bakes_into_keyed_lamps_that_keep_their_ids,
             test_a_bake_of_an_image_sequence_reads_the_scenes_frame_and_restore_takes_the_keys,
             test_sequence_frames_are_the_ones_cycles_renders, test_an_animated_sky_is_rendered_frame_by_frame,
             test_the_tradeoff_says_what_bake_animation_costs,
             test_another_platforms_zip_is_refused_and_the_installed_one_kept])
