"""What a body shows: physics-object hooks, tweens, scripts and particle emitters."""

from __future__ import annotations

from acphys.attachments import AnimHook, ParticleManager
from acphys.constants import EPSILON
from acphys.hooks import FPHook, HookType
from acphys.math.frame import Frame
from acphys.precision import f32


class Effects:
    """Hooks, tweens, scripts and particles (part of :class:`PhysicsObj`)."""

    # -- hooks -----------------------------------------------------------------------------

    def process_hooks(self) -> None:
        """Run every PhysicsObjHook (dropping those that finish), then fire and clear the anim hooks.

        Retail: CPhysicsObj::process_hooks @ 0x00511550 (acclient.c:318640)
        """
        for hook in list(self.hooks):
            if hook.execute(self):
                self.hooks.remove(hook)
        index = 0
        while index < len(self.anim_hooks):
            self.anim_hooks[index].execute(self)
            index += 1
        self.anim_hooks.clear()

    def add_anim_hook(self, hook: AnimHook) -> None:
        """Queue a one-shot animation hook for the next ``process_hooks``.

        Retail: CPhysicsObj::add_anim_hook @ 0x00514C20 (acclient.c:322062)
        """
        self.anim_hooks.append(hook)

    def hook_anim_done(self) -> None:
        """An AnimDone hook fired: tell the part array (and so the motion-table manager).

        Retail: CPhysicsObj::Hook_AnimDone @ 0x0050FDA0 (acclient.c:317086)
        """
        if self.part_array is not None:
            self.part_array.animation_done(True)

    def record_event(self, event: str) -> None:
        """Note in this step's events something the physics does not act on (a sound, a particle)."""
        self.step_events.append(event)

    def process_fp_hook(self, hook_type: HookType, value: float, user_data: int) -> None:
        """Apply one tween value: scale, translucency, a part-array look, or a delayed script.

        ``user_data`` is the part index of the per-part looks and the script id
        of CALL_PES. The part array's lighting and per-part translucency are
        render state acphys does not keep: with a part array they are recorded
        as ``fp_hook:<KIND>:<user_data>=<value>`` events.

        Retail: CPhysicsObj::process_fp_hook @ 0x005135C0 (acclient.c:320571)
        """
        if hook_type == HookType.SCALE:
            self.set_scale_static(value)
        elif hook_type == HookType.TRANSLUCENCY:
            self.set_translucency_internal(value)
        elif hook_type == HookType.CALL_PES:
            self.call_pes_internal(user_data, value)
        elif self.part_array is not None:
            self.record_event(f"fp_hook:{hook_type.name}:{user_data}={value:.6g}")

    def _tween(self, hook_type: HookType, start: float, end: float, delta: float, user_data: int = 0) -> None:
        """Tween from ``start`` to ``end`` over ``delta`` s (≥ EPSILON; newest hook first), else set ``end``.

        The shared shape of SetTranslucency(2), SetPartTranslucency, SetLuminosity,
        SetPartLuminosity, SetDiffusion and SetPartDiffusion: each one's immediate
        branch is the ``process_fp_hook`` case of its kind. ``start`` and ``end`` are ``float``
        parameters in all of them (``delta`` is a double).
        """
        if delta >= EPSILON:
            self.hooks.insert(0, FPHook(hook_type, self.world.physics_time, delta, start, end, user_data))
        else:
            self.process_fp_hook(hook_type, f32(end), user_data)

    def set_translucency_internal(self, translucency: float) -> None:
        """Set translucency, never below ``translucency_original``.

        Retail: CPhysicsObj::SetTranslucencyInternal @ 0x0050F960 (acclient.c:316802)
        """
        self.translucency = max(f32(translucency), self.translucency_original)

    def set_translucency(self, translucency: float, delta: float = 0.0) -> None:
        """Translucency to ``translucency`` now, or over ``delta`` s tweened from 0.0 (not from the
        current value: retail's hook starts at 0).

        Retail: CPhysicsObj::SetTranslucency @ 0x005115F0 (acclient.c:318693)
        """
        self._tween(HookType.TRANSLUCENCY, 0.0, translucency, delta)

    def set_translucency2(self, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetTranslucency2 @ 0x0050FB50 (acclient.c:316920)"""
        self._tween(HookType.TRANSLUCENCY, start, end, delta)

    def set_part_translucency(self, part_index: int, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetPartTranslucency @ 0x00511730 (acclient.c:318758)"""
        self._tween(HookType.PART_TRANSLUCENCY, start, end, delta, part_index)

    def set_luminosity(self, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetLuminosity @ 0x00511890 (acclient.c:318826)"""
        self._tween(HookType.LUMINOSITY, start, end, delta)

    def set_part_luminosity(self, part_index: int, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetPartLuminosity @ 0x005117E0 (acclient.c:318792)"""
        self._tween(HookType.PART_LUMINOSITY, start, end, delta, part_index)

    def set_diffusion(self, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetDiffusion @ 0x005119E0 (acclient.c:318894)"""
        self._tween(HookType.DIFFUSION, start, end, delta)

    def set_part_diffusion(self, part_index: int, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetPartDiffusion @ 0x00511930 (acclient.c:318860)"""
        self._tween(HookType.PART_DIFFUSION, start, end, delta, part_index)

    # -- scripts and particles -------------------------------------------------------------

    def call_pes(self, pes: int, delta: float) -> None:
        """Play script ``pes`` now, or after a random pause in [0, ``delta``] (a CALL_PES hook).

        The dice's upper bound and the pause it rolls are ``float`` (acclient.c:318986-318987).

        Retail: CPhysicsObj::CallPES @ 0x00511AF0 (acclient.c:318972)
        """
        if delta >= EPSILON:
            pause = f32(self.world.dice.uniform(0.0, f32(delta)))
            self.hooks.insert(0, FPHook(HookType.CALL_PES, self.world.physics_time, pause, 0.0, 1.0, pes))
        elif self.cell is not None:
            self.play_script_internal(pes)

    def call_pes_internal(self, pes: int, cur_value: float) -> None:
        """The CALL_PES hook's tick: play ``pes`` once the tween has reached 1 (body in a cell).

        Retail: CPhysicsObj::CallPESInternal @ 0x00511AC0 (acclient.c:318962)
        """
        if cur_value >= 1.0 and self.cell is not None:
            self.play_script_internal(pes)

    def play_script_internal(self, script_id: int) -> bool:
        """Queue script ``script_id`` on the script manager (made here when missing); False for id 0.

        Retail: CPhysicsObj::play_script_internal @ 0x00510CD0 (acclient.c:318034)
        """
        if not script_id:
            return False
        if self.script_manager is None:
            from acphys.managers.scripts import ScriptManager as RetailScriptManager

            self.script_manager = RetailScriptManager(self)
        return self.script_manager.add_script(script_id)

    def play_script(self, script_id: int) -> bool:
        """Play script ``script_id``; a body outside the world only answers True.

        Retail: CPhysicsObj::play_script @ 0x00510D30 (acclient.c:318069)
        """
        if self.cell is None:
            return True
        return self.play_script_internal(script_id)

    def play_script_type(self, script_type: int, mod: float) -> bool:
        """Play the ``physics_script_table``'s script for ``script_type`` at intensity ``mod``
        (retail's ``play_script(PScriptType, float)`` overload: ``mod`` is narrowed to float32).

        Retail: CPhysicsObj::play_script @ 0x00513260 (acclient.c:320325)
        """
        if self.cell is None:
            return True
        if self.physics_script_table is None:
            return False
        return self.play_script_internal(self.physics_script_table.get_script(script_type, f32(mod)))

    def play_default_script(self) -> bool:
        """Play ``default_script`` at ``default_script_intensity`` from the script table.

        Retail: CPhysicsObj::play_default_script @ 0x005132B0 (acclient.c:320350)
        """
        return self.play_script_type(self.default_script, self.default_script_intensity)

    def _make_particle_manager(self) -> ParticleManager:
        """The particle manager, made first when the body has none (inline in the create calls)."""
        if self.particle_manager is None:
            from acphys.managers.particles import ParticleManager as RetailParticleManager

            self.particle_manager = RetailParticleManager()
        return self.particle_manager

    def create_particle_emitter(
        self, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int:
        """Start an emitter (replacing one with the same non-zero ``emitter_id``); its id, or 0.

        Retail: CPhysicsObj::create_particle_emitter @ 0x0050F360 (acclient.c:316329)
        """
        manager = self._make_particle_manager()
        return manager.create_particle_emitter(self, emitter_info_id, part_index, offset, emitter_id)

    def create_blocking_particle_emitter(
        self, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int:
        """Start an emitter unless ``emitter_id`` is already playing; its id, or 0.

        Retail: CPhysicsObj::create_blocking_particle_emitter @ 0x0050F3B0 (acclient.c:316355)
        """
        manager = self._make_particle_manager()
        return manager.create_blocking_particle_emitter(self, emitter_info_id, part_index, offset, emitter_id)

    def destroy_particle_emitter(self, emitter_id: int) -> bool:
        """Retail: CPhysicsObj::destroy_particle_emitter @ 0x0050F400 (acclient.c:316381)"""
        manager = self.particle_manager
        return manager is not None and manager.destroy_particle_emitter(emitter_id)

    def stop_particle_emitter(self, emitter_id: int) -> bool:
        """Retail: CPhysicsObj::stop_particle_emitter @ 0x0050F420 (acclient.c:316395)"""
        return self.particle_manager is not None and self.particle_manager.stop_particle_emitter(emitter_id)

    def get_num_emitters(self) -> int:
        """Retail: CPhysicsObj::get_num_emitters @ 0x0050F440 (acclient.c:316409)"""
        return self.particle_manager.get_num_emitters() if self.particle_manager is not None else 0

    def set_scale(self, new_scale: float, delta: float = 0.0) -> None:
        """Scale the body now, or tween to ``new_scale`` over ``delta`` seconds (≥ EPSILON).

        Retail: CPhysicsObj::SetScale @ 0x005136A0 (acclient.c:320621)
        """
        if delta >= EPSILON:
            hook = FPHook(HookType.SCALE, self.world.physics_time, delta, self.scale, new_scale)
            self.hooks.insert(0, hook)
        else:
            self.set_scale_static(new_scale)

    def set_scale_static(self, new_scale: float) -> None:
        """Scale the body and its part array now.

        ``new_scale`` is a ``float`` parameter, stored in ``m_scale`` and the part array's scale.

        Retail: CPhysicsObj::SetScaleStatic @ 0x00511BB0 (acclient.c:319007)
        """
        new_scale = f32(new_scale)
        self.scale = new_scale
        if self.part_array is not None:
            self.part_array.set_scale_internal(new_scale)
