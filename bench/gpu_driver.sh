# Sourced by the bench scripts that run on the GPU machine (the device tool, carrying `.gl`):
# unpacks the Vulkan loader and GL packages kept in .gl (the device tool: its README says how to fetch them) and points the
# loader at NVIDIA's driver. Does nothing where .gl holds no packages (a machine with its own
# loader, or lavapipe here).
if compgen -G ".gl/*.deb" > /dev/null; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
    export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
