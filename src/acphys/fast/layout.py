"""The fast engine's arrays: one record per body, one per transition, and the world's cells.

Every number is stored as a float64 (``f8``), although most hold float32 values (retail's
``float`` fields): Numba computes an operation between two float32s in float32, where retail's x87
and the reference engine compute in double, so float32 storage would round reads wrongly. The
kernels narrow with ``f32`` at every store where the reference does, exactly as it does.

A body's record holds what one step reads and writes (position, velocities, contact, the
sequence, its shadows in cells); everything else stays on the reference ``PhysicsObj``, which
the kernel covers only while that rest is idle (see :mod:`acphys.fast.coverage`). Records are in
the order of retail's object table, the order ``CPhysics::UseTime`` runs them: one row per body,
the fields of a step side by side (the loop is sequential; a step touches all of one row).
"""

from __future__ import annotations

import numpy as np

#: The most spheres a sweep takes (``SPHEREPATH::init_sphere`` keeps the first two).
MAX_SPHERES = 2
#: The most cells one body's shadows are in, and the most cells a sweep's cell array holds.
#: Two spheres of at most 12 m reach at most four land cells; more than this falls back.
MAX_CELLS = 8
#: The most nodes of a sequence the kernel plays (links then cycles); more falls back.
MAX_NODES = 4
#: The most collision records (``collision_table``) a covered body holds.
MAX_RECORDS = 4
#: The most nodes of each motion queue an AnimDone hook retires (the motion table's pending
#: animations, the motion interpreter's pending motions) the kernel holds; a longer queue's hooks
#: are the reference path's.
MAX_PENDING = 4
#: The most bodies one sweep touches (``COLLISIONINFO::collide_object``); more falls back.
MAX_COLLIDE = 4

BODY = np.dtype(
    [
        # -- which path runs the body, and whether its PhysicsObj is behind ------------------
        ("covered", "u1"),  # the reference-side state is idle: the kernel may step this body
        ("stale", "u1"),  # the kernel stepped the body since its PhysicsObj was last written
        ("obj_id", "u4"),
        # -- CPhysicsObj -------------------------------------------------------------------
        ("state", "u4"),
        ("transient", "u4"),
        ("update_time", "f8"),
        ("player_distance", "f8"),
        ("player_vector", "f8", 3),
        ("cell_id", "u4"),  # position.objcell_id
        ("cell", "i4"),  # the kernel index of the cell the body is in (-1: none)
        ("origin", "f8", 3),
        ("q", "f8", 4),  # (w, x, y, z)
        ("m", "f8", 9),  # the cached matrix, m_fl2gv
        ("velocity", "f8", 3),
        ("acceleration", "f8", 3),
        ("omega", "f8", 3),
        ("cached_velocity", "f8", 3),
        ("friction", "f8"),
        ("elasticity", "f8"),
        ("scale", "f8"),
        ("contact_n", "f8", 3),
        ("contact_d", "f8"),
        ("contact_cell_id", "u4"),
        ("sliding_normal", "f8", 3),
        ("jumped_this_frame", "u1"),
        ("step_events", "u1"),  # the object holds events for the next step's record (step_events)
        ("has_parent", "u1"),
        ("reach", "f8"),  # how far its spheres reach from its origin (+ REACH_MARGIN), for the grid
        ("hreach", "f8"),  # the same across the ground while the body is upright (acphys.fast.kernels.grid)
        ("collider", "u1"),  # a body of spheres only, no weenie: the kernel can answer for it
        ("on_collision", "u1"),  # a user's collision callback: reports to it are the reference's
        ("colliding_with_environment", "u1"),
        # collision_table: whom each record is of, when it was last touched, whether it was ethereal
        ("num_records", "i1"),
        ("record_obj", "u4", MAX_RECORDS),
        ("record_time", "f8", MAX_RECORDS),
        ("record_ethereal", "u1", MAX_RECORDS),
        ("has_movement_manager", "u1"),
        ("glide", "i4"),  # its row of the interpolation table (INTERPOLATION), -1: no position manager
        # -- the setup (CPartArray) ----------------------------------------------------------
        ("num_sphere", "i1"),
        ("sphere", "f8", (MAX_SPHERES, 4)),  # centre x, y, z and radius, unscaled
        ("step_up_height", "f8"),
        ("step_down_height", "f8"),
        ("free_heading", "u1"),  # the setup allows a free heading (the sweep takes FREE_ROTATE)
        # -- the shadows (CPhysicsObj::shadow_objects), in order --------------------------------
        ("num_shadow", "i1"),
        ("shadows_moved", "u1"),  # the kernel cast the shadows again since the object was written
        ("shadow_cell", "i4", MAX_CELLS),  # kernel cell index, -1 for an id with no cell
        ("shadow_cell_id", "u4", MAX_CELLS),
        ("shadow_slot", "i4", MAX_CELLS),  # the shadow's index in its cell's list
        ("grid_bucket", "i4"),  # the broad-phase grid bucket the body is filed in (-1: none)
        ("grid_next", "i4"),
        ("grid_prev", "i4"),
        # -- the sequence (CSequence) -------------------------------------------------------------
        ("seq_nodes", "i1"),  # 0: no animation list
        ("seq_curr", "i1"),
        ("seq_first_cyclic", "i1"),
        ("seq_anim", "i4", MAX_NODES),  # index into the animation table
        ("seq_framerate", "f8", MAX_NODES),
        ("seq_low", "i4", MAX_NODES),
        ("seq_high", "i4", MAX_NODES),
        ("seq_frame_number", "f8"),
        ("seq_velocity", "f8", 3),
        ("seq_omega", "f8", 3),
        ("seq_anim_done", "i4"),  # the AnimDone hooks the last quantum queued
        # the terms of the sequence's last turn (Frame::grotate's angle: squared, 1/angle, the sine
        # and cosine of its half), reused while its squared angle repeats (frame.grotate_remembered)
        ("turn_memo", "f8", 4),
        # -- the motion queues an AnimDone hook retires (acphys.fast.kernels.motion_queues) ------
        # MotionTableManager::pending_animations: its length (-1: the kernel leaves the queue's
        # hooks to the reference path), animation_counter, and head first each node's num_anims
        # and whether its motion is no action (completing it pops no action queue)
        ("table_len", "i1"),
        ("table_counter", "i4"),
        ("table_anims", "i4", MAX_PENDING),
        ("table_plain", "u1", MAX_PENDING),
        # CMotionInterp::pending_motions the table's MotionDone pops: its length (-1: unknown)
        # and, head first, whether each node's motion is no action
        ("interp_len", "i1"),
        ("interp_plain", "u1", MAX_PENDING),
        ("motions_owed", "u1"),  # an AnimDone hook waits for the engine: the body's later ones wait too
    ]
)

#: The most nodes of an interpolation queue the kernel holds: retail's bound (acclient.c:389084).
MAX_GLIDE_NODES = 20

#: A covered body's ``PositionManager`` with its ``InterpolationManager`` (the only sub-manager a
#: covered body may have): the queue of server positions, head first at ``first``, and the audit's
#: state. One row per such body (``BODY.glide``); a body's glide is read with its record.
INTERPOLATION = np.dtype(
    [
        ("loaded", "i4"),  # the nodes the queue held when the row was read
        ("first", "i4"),  # the head node's index (the kernel drops nodes from the head only)
        ("num_nodes", "i4"),
        ("keep_heading", "u1"),
        ("frame_counter", "i4"),
        ("node_fail_counter", "i4"),
        ("original_distance", "f8"),
        ("progress_quantum", "f8"),
        ("max_speed", "f8"),  # the motion interpreter's get_adjusted_max_speed (steps leave it)
        ("node_cell_id", "u4", MAX_GLIDE_NODES),
        ("node_origin", "f8", (MAX_GLIDE_NODES, 3)),
        ("node_q", "f8", (MAX_GLIDE_NODES, 4)),
        ("node_m", "f8", (MAX_GLIDE_NODES, 9)),
    ]
)

#: One land cell of a loaded landblock: its two terrain triangles (vertices and planes) and what
#: the kernel must leave to the reference path.
CELL = np.dtype(
    [
        ("cell_id", "u4"),
        ("landblock", "i4"),  # index of its landblock in the landblock table
        ("water_type", "i1"),
        ("block_water_type", "i1"),
        ("num_polys", "i1"),  # 2, or 0 for a cell without terrain
        ("vertex", "f8", (2, 3, 3)),  # triangle, vertex, xyz (landblock-local)
        ("plane", "f8", (2, 4)),  # normal x, y, z and d
        ("uncovered", "u1"),  # voyeurs, a building it cannot bound, or anything else the kernel lacks
        # a building the kernel can bound (acphys.fast.buildings): its shell's ball (a row of the
        # building shapes, -1: a shell that answers OK) and the planes of its doors' cells
        ("building", "u1"),
        ("building_ball", "i4"),
        ("building_doors", "i4"),  # its first row of the door spans
        ("num_building_doors", "i4"),
        ("dirty", "u1"),  # the kernel changed the shadow list since the reference cell was written
        ("num_shadows", "i4"),
        ("num_others", "i4"),  # shadows of objects that are not the engine's bodies (static objects)
        ("shadow_start", "i4"),  # where the cell's shadow list starts in the shadow pool
        ("shadow_capacity", "i4"),
    ]
)

#: The transition the kernel sweeps with: SPHEREPATH, COLLISIONINFO and OBJECTINFO fields and the
#: cell array. Retail hands out a pooled transition whose fields outlive a sweep; this record is
#: that slot (``CTransition::makeTransition``), kept from body to body.
TRANSITION = np.dtype(
    [
        # -- what one sweep leaves to the next (the first CARRIED bytes: all an update handed back
        # restores; every other field is set afresh by the next sweep before it is read)
        ("walk_interp", "f8"),
        ("step_down_amt", "f8"),
        ("backup", "i1"),
        ("last_known_contact_n", "f8", 3),
        ("last_known_contact_d", "f8"),
        ("last_known_contact_plane_is_water", "u1"),
        ("last_known_contact_plane_cell_id", "u4"),
        ("contact_n", "f8", 3),
        ("contact_d", "f8"),
        ("contact_plane_is_water", "u1"),
        ("sliding_normal", "f8", 3),
        ("collision_normal", "f8", 3),
        ("collide_body", "i4", MAX_COLLIDE),  # the bodies touched, by index
        # the last cell list found (find_cell_list is a function of the cell id and the spheres'
        # x, y and radii): reused while those stay the same
        ("memo_valid", "u1"),
        ("memo_cell_id", "u4"),
        ("memo_num_sphere", "i1"),
        ("memo_spheres", "f8", (MAX_SPHERES, 3)),
        ("memo_num_cells", "i4"),
        ("memo_cells", "i4", MAX_CELLS),
        ("memo_cell_ids", "u4", MAX_CELLS),
        ("memo_curr", "i4"),  # the cell holding sphere 0's centre, -1 for none
        # -- set afresh by every sweep
        # OBJECTINFO
        ("oi_state", "u4"),
        ("oi_scale", "f8"),
        ("oi_step_up_height", "f8"),
        ("oi_step_down_height", "f8"),
        ("oi_step_down", "u1"),
        ("oi_body", "i4"),
        # SPHEREPATH
        ("num_sphere", "i1"),
        ("local_sphere", "f8", (MAX_SPHERES, 4)),
        ("local_low_point", "f8", 3),
        ("global_sphere", "f8", (MAX_SPHERES, 4)),
        ("global_low_point", "f8", 3),
        ("global_curr_center", "f8", (MAX_SPHERES, 3)),
        ("begin_cell", "i4"),
        ("begin_cell_id", "u4"),
        ("begin_origin", "f8", 3),
        ("begin_q", "f8", 4),
        ("end_cell_id", "u4"),
        ("end_origin", "f8", 3),
        ("end_q", "f8", 4),
        ("curr_cell", "i4"),
        ("curr_cell_id", "u4"),
        ("curr_origin", "f8", 3),
        ("curr_q", "f8", 4),
        ("curr_m", "f8", 9),
        ("check_cell", "i4"),
        ("check_cell_id", "u4"),
        ("check_origin", "f8", 3),
        ("check_q", "f8", 4),
        ("check_m", "f8", 9),
        ("backup_cell", "i4"),
        ("backup_cell_id", "u4"),
        ("backup_origin", "f8", 3),
        ("backup_q", "f8", 4),
        ("backup_m", "f8", 9),
        ("global_offset", "f8", 3),
        ("insert_type", "i1"),
        ("step_up", "u1"),
        ("step_down", "u1"),
        ("collide", "u1"),
        ("neg_poly_hit", "u1"),
        ("check_walkable", "u1"),
        ("cell_array_valid", "u1"),
        ("hits_interior_cell", "u1"),
        ("walkable", "u1"),  # a walkable polygon is recorded (the kernel never records one)
        ("walkable_allowance", "f8"),
        # COLLISIONINFO
        ("last_known_contact_plane_valid", "u1"),
        ("contact_plane_valid", "u1"),
        ("contact_plane_cell_id", "u4"),
        ("sliding_normal_valid", "u1"),
        ("collision_normal_valid", "u1"),
        ("collided_with_environment", "u1"),
        ("frames_stationary_fall", "i4"),
        ("num_collide", "i4"),
        # CELLARRAY
        ("num_cells", "i4"),
        ("added_outside", "u1"),
        ("cells", "i4", MAX_CELLS),  # kernel cell index, -1 for an id with no cell
        ("cell_ids", "u4", MAX_CELLS),
        # the kernel's own: why the last step was handed back (acphys.fast.kernels.cells.BAIL_REASONS)
        ("bail", "i4"),
        ("unread_cell", "u4"),  # with bail R_UNREAD: the land cell whose landblock the arrays lack
        # no other body is filed near the whole sweep: every body's find_obj_collisions is OK
        ("lonely", "u1"),
        # the last terrain triangle found under a point in this sweep (find_terrain_poly is a
        # function of the cell and the point's x and y; a step down or a lift moves z alone)
        ("poly_memo_cell", "i4"),  # -1: none
        ("poly_memo_x", "f8"),
        ("poly_memo_y", "f8"),
        ("poly_memo", "i4"),
    ]
)
#: The bytes of a transition record one sweep leaves to the next: a body's update saves them
#: before it starts and restores them when it is handed back (its sweep's own fields are dead then:
#: the reference path's sweep sets each afresh before it reads it).
CARRIED = TRANSITION.fields["oi_state"][1]

#: The bytes of a plane in the records: its normal ``*_n`` then its distance ``*_d``, side by side
#: (the contact planes of BODY and TRANSITION, the transition's last known contact plane), copied
#: at once (:func:`acphys.fast.kernels.store.copy_span`).
PLANE_BYTES = 32
