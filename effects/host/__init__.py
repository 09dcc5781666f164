"""What a host application supplies around an effect: runtime, scene, bindings, assets."""
