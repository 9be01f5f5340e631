/*
 * shader-stats: compiles one shader on whatever GPU driver the environment selects, and prints
 * what the driver's compiler reports about it. It is the part of the cost model that must run
 * inside the driver's process: built for amd64 (RADV, radeonsi, nouveau) and for arm64 (turnip,
 * freedreno, panvk, panfrost, run under qemu-user), with Mesa's drm-shim preloaded so that the
 * production compilers run with no GPU present. It knows nothing of any one driver's statistics:
 * the Rust side (gbuffer-cost) reads them.
 *
 *   shader-stats gl     STAGE SHADER [VERTEX] [-- STAGE SHADER [VERTEX]]...
 *       GLSL ES through EGL surfaceless. Prints `renderer: ...`, `version: ...`, then for each
 *       shader `shader: N` and each KHR_debug message as `message: ...` (where Mesa's shader-db
 *       statistics arrive), or `error: ...` where it does not compile or link.
 *   shader-stats vulkan STAGE SHADER.spv [VERTEX.spv] [--entry NAME] [--vertex-entry NAME]
 *                       [--descriptor SET,BINDING,KIND]...
 *                       [--color FORMAT]... [--attribute FORMAT]... [--push-constants BYTES]
 *                       [--rendering MODE] [--disassembly] [-- STAGE SHADER.spv ...]...
 *       SPIR-V through VK_KHR_pipeline_executable_properties. Prints `device: ...`,
 *       `driver: ...`, then for each shader `shader: N`, per executable `executable: NAME` and
 *       `statistic: NAME = VALUE`, with --disassembly `representation: NAME` followed by its
 *       text and `end-representation`, or `error: ...` where the pipeline cannot be created.
 *
 *       MODE says what a graphics pipeline is created for: `render-pass` (the default), a
 *       render pass object of one subpass whose input attachments are attachments of their own;
 *       `local-read`, a dynamic rendering read through VK_KHR_dynamic_rendering_local_read,
 *       input attachment index i being colour attachment i (as a fused G-buffer pass reads the
 *       attachments it writes); `local-read-ordered`, that with rasterization-order colour
 *       attachment access (VK_EXT_rasterization_order_attachment_access, or ARM's). A device
 *       without what the mode needs gets the shader an `error:` line naming it. Each
 *       --attribute is a vertex input at the next location, in a binding of its own; the push
 *       constants are BYTES visible to every stage.
 *
 * Several shaders separated by `--` compile in one process: starting the driver (under qemu,
 * most of a run) is paid once.
 *
 * STAGE is `vertex`, `fragment` or `compute`; NAME the SPIR-V entry point (default `main`, for
 * the shader's and the vertex shader's alike). A fragment shader needs a vertex shader to link
 * against (GLSL ES links the pair; a Vulkan pipeline needs both). KIND is one of uniform,
 * storage, sampled, sampler, combined, storage-image, input-attachment; a colour's FORMAT one of
 * r32ui, rg32ui, rgba32ui, r32i, rgba32i, r32f, rgba32f, rgba16f, rgba8, rgb10a2, rg11b10f; an
 * attribute's one of r32ui, r32f, rg32f, rgb32f, rgba32f.
 *
 * Exit status: 0 when the driver started (each shader's own failure is its `error:` line), 1
 * when it did not (a one-line reason on stderr), 2 usage. Every API entry point is loaded with dlopen, so the program needs no GPU headers'
 * libraries at link time and cross-compiles with nothing but a C compiler and its libc.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLES_PROTOTYPES 0
#include <GLES3/gl32.h>
#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

/* VK_KHR_dynamic_rendering_local_read (Vulkan 1.3.278, core in 1.4) is newer than Debian 12's
 * headers (1.3.239): its names and structures as the Vulkan registry defines them. */
#ifndef VK_KHR_dynamic_rendering_local_read
#define VK_KHR_DYNAMIC_RENDERING_LOCAL_READ_EXTENSION_NAME "VK_KHR_dynamic_rendering_local_read"
#define VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_LOCAL_READ_FEATURES_KHR                \
    ((VkStructureType)1000232000)
#define VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_LOCATION_INFO_KHR ((VkStructureType)1000232001)
#define VK_STRUCTURE_TYPE_RENDERING_INPUT_ATTACHMENT_INDEX_INFO_KHR ((VkStructureType)1000232002)
typedef struct {
    VkStructureType sType;
    void *pNext;
    VkBool32 dynamicRenderingLocalRead;
} VkPhysicalDeviceDynamicRenderingLocalReadFeaturesKHR;
typedef struct {
    VkStructureType sType;
    const void *pNext;
    uint32_t colorAttachmentCount;
    const uint32_t *pColorAttachmentLocations;
} VkRenderingAttachmentLocationInfoKHR;
typedef struct {
    VkStructureType sType;
    const void *pNext;
    uint32_t colorAttachmentCount;
    const uint32_t *pColorAttachmentInputIndices;
    const uint32_t *pDepthInputAttachmentIndex;
    const uint32_t *pStencilInputAttachmentIndex;
} VkRenderingInputAttachmentIndexInfoKHR;
#endif

/* While a shader is being compiled, a failure is that shader's: it is printed as its `error:`
 * line and the next shader goes on. Before (the driver starting), it ends the program. */
static jmp_buf *this_shader;

static void fail(const char *format, ...) {
    va_list args;
    va_start(args, format);
    FILE *out = this_shader ? stdout : stderr;
    fputs(this_shader ? "error: " : "shader-stats: ", out);
    vfprintf(out, format, args);
    fputc('\n', out);
    va_end(args);
    if (this_shader) longjmp(*this_shader, 1);
    exit(1);
}

typedef void (*compile_function)(void *context, int argc, char **argv);

static void guarded(compile_function compile, void *context, int argc, char **argv) {
    jmp_buf recover;
    if (!setjmp(recover)) {
        this_shader = &recover;
        compile(context, argc, argv);
    }
    this_shader = NULL;
}

/* Compiles each group of arguments (separated by `--`) after a `shader: N` line. */
static void each_shader(int argc, char **argv, compile_function compile, void *context) {
    for (int start = 0, index = 0; start < argc; index++) {
        int end = start;
        while (end < argc && strcmp(argv[end], "--")) end++;
        printf("shader: %d\n", index);
        guarded(compile, context, end - start, argv + start);
        start = end + 1;
    }
}

static void usage(void) {
    fputs("usage: shader-stats gl STAGE SHADER [VERTEX]\n"
          "       shader-stats vulkan STAGE SHADER.spv [VERTEX.spv] [--entry NAME] [--vertex-entry NAME]"
          " [--descriptor SET,BINDING,KIND]... [--color FORMAT]... [--attribute FORMAT]..."
          " [--push-constants BYTES] [--rendering MODE] [--disassembly]\n",
          stderr);
    exit(2);
}

/* The whole file, NUL-terminated; its length in *length when asked. */
static char *read_file(const char *path, size_t *length) {
    FILE *file = fopen(path, "rb");
    if (!file) fail("cannot read %s", path);
    size_t capacity = 1 << 16, used = 0;
    char *bytes = malloc(capacity);
    size_t got;
    while (bytes && (got = fread(bytes + used, 1, capacity - used - 1, file)) > 0) {
        used += got;
        if (used + 1 == capacity) bytes = realloc(bytes, capacity *= 2);
    }
    fclose(file);
    if (!bytes) fail("out of memory reading %s", path);
    bytes[used] = 0;
    if (length) *length = used;
    return bytes;
}

static void *library(const char *name) {
    void *handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (!handle) fail("cannot load %s: %s", name, dlerror());
    return handle;
}

/* ---- GLES through EGL surfaceless ---------------------------------------------------------- */

static void GL_APIENTRY on_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity,
                                         GLsizei length, const GLchar *message, const void *user) {
    (void)source, (void)type, (void)id, (void)severity, (void)user;
    /* One record a line: a message that spans lines keeps its lines, each prefixed. */
    const char *line = message;
    const char *end = length >= 0 ? message + length : message + strlen(message);
    while (line < end) {
        const char *newline = memchr(line, '\n', (size_t)(end - line));
        const char *stop = newline ? newline : end;
        if (stop > line) printf("message: %.*s\n", (int)(stop - line), line);
        line = stop + 1;
    }
}

static GLenum gl_stage(const char *stage) {
    if (!strcmp(stage, "vertex")) return GL_VERTEX_SHADER;
    if (!strcmp(stage, "fragment")) return GL_FRAGMENT_SHADER;
    if (!strcmp(stage, "compute")) return GL_COMPUTE_SHADER;
    usage();
    return 0;
}

#define GL_FUNCTIONS(X)                                                                           \
    X(PFNGLGETSTRINGPROC, glGetString)                                                           \
    X(PFNGLENABLEPROC, glEnable)                                                                 \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, glDebugMessageCallback)                                     \
    X(PFNGLDEBUGMESSAGECONTROLPROC, glDebugMessageControl)                                       \
    X(PFNGLCREATESHADERPROC, glCreateShader)                                                     \
    X(PFNGLSHADERSOURCEPROC, glShaderSource)                                                     \
    X(PFNGLCOMPILESHADERPROC, glCompileShader)                                                   \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                                       \
    X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                                             \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                                   \
    X(PFNGLATTACHSHADERPROC, glAttachShader)                                                     \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                                       \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                                     \
    X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                                           \
    X(PFNGLFINISHPROC, glFinish)

#define DECLARE(type, name) static type name;
GL_FUNCTIONS(DECLARE)

/* A driver's log on one line, as every message of this program is. */
static const char *one_line(char *log) {
    for (char *c = log; *c; c++)
        if (*c == '\n') *c = ' ';
    return log;
}

static GLuint gl_compile(GLenum stage, const char *path) {
    const char *source = read_file(path, NULL);
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, NULL);
    glCompileShader(shader);
    GLint compiled = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
        char log[4096] = "";
        glGetShaderInfoLog(shader, sizeof log, NULL, log);
        fail("%s does not compile: %s", path, one_line(log));
    }
    return shader;
}

/* One program: STAGE SHADER [VERTEX]. */
static void gl_program(void *unused, int argc, char **argv) {
    (void)unused;
    if (argc < 2 || argc > 3) usage();
    GLenum stage = gl_stage(argv[0]);
    if (stage == GL_FRAGMENT_SHADER && argc != 3) fail("a fragment shader needs a vertex shader");
    GLuint program = glCreateProgram();
    glAttachShader(program, gl_compile(stage, argv[1]));
    if (argc == 3) glAttachShader(program, gl_compile(GL_VERTEX_SHADER, argv[2]));
    glLinkProgram(program);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        char log[4096] = "";
        glGetProgramInfoLog(program, sizeof log, NULL, log);
        fail("the program does not link: %s", one_line(log));
    }
    glFinish();
}

static int run_gl(int argc, char **argv) {
    if (argc < 2) usage();
    void *egl = library("libEGL.so.1");
    PFNEGLGETPROCADDRESSPROC get = (PFNEGLGETPROCADDRESSPROC)dlsym(egl, "eglGetProcAddress");
    if (!get) fail("libEGL.so.1 has no eglGetProcAddress");
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)get("eglGetPlatformDisplayEXT");
    PFNEGLINITIALIZEPROC initialize = (PFNEGLINITIALIZEPROC)get("eglInitialize");
    PFNEGLBINDAPIPROC bind_api = (PFNEGLBINDAPIPROC)get("eglBindAPI");
    PFNEGLCREATECONTEXTPROC create_context = (PFNEGLCREATECONTEXTPROC)get("eglCreateContext");
    PFNEGLMAKECURRENTPROC make_current = (PFNEGLMAKECURRENTPROC)get("eglMakeCurrent");
    if (!get_display || !initialize || !bind_api || !create_context || !make_current)
        fail("EGL lacks eglGetPlatformDisplayEXT or a core entry point");

    EGLDisplay display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (display == EGL_NO_DISPLAY || !initialize(display, &major, &minor))
        fail("no EGL surfaceless display");
    if (!bind_api(EGL_OPENGL_ES_API)) fail("EGL cannot bind OpenGL ES");
    /* The newest GLES the driver offers, with debug output so that statistics arrive. */
    static const EGLint versions[][2] = {{3, 2}, {3, 1}, {3, 0}};
    EGLContext context = EGL_NO_CONTEXT;
    for (unsigned i = 0; i < 3 && context == EGL_NO_CONTEXT; i++) {
        EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, versions[i][0],
                               EGL_CONTEXT_MINOR_VERSION, versions[i][1],
                               EGL_CONTEXT_OPENGL_DEBUG,  EGL_TRUE,
                               EGL_NONE};
        context = create_context(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    }
    if (context == EGL_NO_CONTEXT) fail("no OpenGL ES 3 context");
    if (!make_current(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        fail("cannot make the OpenGL ES context current");

#define LOAD(type, name)                                                                          \
    if (!(name = (type)get(#name))) fail("OpenGL ES lacks " #name);
    GL_FUNCTIONS(LOAD)

    printf("renderer: %s\n", (const char *)glGetString(GL_RENDERER));
    printf("version: %s\n", (const char *)glGetString(GL_VERSION));
    fflush(stdout);
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(on_debug_message, NULL);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_TRUE);

    each_shader(argc, argv, gl_program, NULL);
    return 0;
}

/* ---- Vulkan through VK_KHR_pipeline_executable_properties ---------------------------------- */

#define MAX_ITEMS 32

struct descriptor {
    uint32_t set, binding;
    VkDescriptorType type;
};

/* A name on the command line and the Vulkan enumerant it stands for. */
struct named {
    const char *name;
    int value;
};

static const struct named descriptor_kinds[] = {
    {"uniform", VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
    {"storage", VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
    {"sampled", VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
    {"sampler", VK_DESCRIPTOR_TYPE_SAMPLER},
    {"combined", VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
    {"storage-image", VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
    {"input-attachment", VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT},
    {NULL, 0},
};

static const struct named color_formats[] = {
    {"r32ui", VK_FORMAT_R32_UINT},
    {"rg32ui", VK_FORMAT_R32G32_UINT},
    {"rgba32ui", VK_FORMAT_R32G32B32A32_UINT},
    {"r32i", VK_FORMAT_R32_SINT},
    {"rgba32i", VK_FORMAT_R32G32B32A32_SINT},
    {"r32f", VK_FORMAT_R32_SFLOAT},
    {"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT},
    {"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT},
    {"rgba8", VK_FORMAT_R8G8B8A8_UNORM},
    {"rgb10a2", VK_FORMAT_A2B10G10R10_UNORM_PACK32},
    {"rg11b10f", VK_FORMAT_B10G11R11_UFLOAT_PACK32},
    {NULL, 0},
};

/* A vertex attribute's format and its size in bytes. */
struct attribute_format {
    const char *name;
    VkFormat format;
    uint32_t bytes;
};

static const struct attribute_format attribute_formats[] = {
    {"r32ui", VK_FORMAT_R32_UINT, 4},
    {"r32f", VK_FORMAT_R32_SFLOAT, 4},
    {"rg32f", VK_FORMAT_R32G32_SFLOAT, 8},
    {"rgb32f", VK_FORMAT_R32G32B32_SFLOAT, 12},
    {"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT, 16},
    {NULL, 0, 0},
};

static struct attribute_format attribute_format(const char *name) {
    for (const struct attribute_format *format = attribute_formats; format->name; format++)
        if (!strcmp(name, format->name)) return *format;
    usage();
    return attribute_formats[0];
}

/* What a graphics pipeline is created for (--rendering). */
enum rendering { RENDER_PASS, LOCAL_READ, LOCAL_READ_ORDERED };

static const struct named renderings[] = {
    {"render-pass", RENDER_PASS},
    {"local-read", LOCAL_READ},
    {"local-read-ordered", LOCAL_READ_ORDERED},
    {NULL, 0},
};

/* The value `name` stands for in `table`; a name not there is a usage error. */
static int named_value(const struct named *table, const char *name) {
    for (; table->name; table++)
        if (!strcmp(name, table->name)) return table->value;
    usage();
    return 0;
}

static PFN_vkGetInstanceProcAddr instance_function;
static PFN_vkGetDeviceProcAddr device_function;

#define CHECK(call, what)                                                                         \
    do {                                                                                          \
        VkResult result_ = (call);                                                                \
        if (result_ != VK_SUCCESS) fail("%s failed (VkResult %d)", what, (int)result_);           \
    } while (0)

static VkShaderModule shader_module(VkDevice device, const char *path) {
    size_t length;
    char *words = read_file(path, &length);
    if (length == 0 || length % 4) fail("%s is not SPIR-V (its length is not whole words)", path);
    PFN_vkCreateShaderModule create =
        (PFN_vkCreateShaderModule)device_function(device, "vkCreateShaderModule");
    VkShaderModuleCreateInfo info = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                     .codeSize = length,
                                     .pCode = (const uint32_t *)words};
    VkShaderModule module;
    CHECK(create(device, &info, NULL, &module), "vkCreateShaderModule");
    return module;
}

/* One descriptor set layout per set number up to the highest named, empty where none is. */
static VkPipelineLayout pipeline_layout(VkDevice device, const struct descriptor *descriptors,
                                        unsigned count, uint32_t push_constant_bytes) {
    PFN_vkCreateDescriptorSetLayout create_set =
        (PFN_vkCreateDescriptorSetLayout)device_function(device, "vkCreateDescriptorSetLayout");
    PFN_vkCreatePipelineLayout create_layout =
        (PFN_vkCreatePipelineLayout)device_function(device, "vkCreatePipelineLayout");
    uint32_t sets = 0;
    for (unsigned i = 0; i < count; i++)
        if (descriptors[i].set + 1 > sets) sets = descriptors[i].set + 1;
    if (sets > 8) fail("descriptor sets above 7 are not supported");
    VkDescriptorSetLayout set_layouts[8];
    for (uint32_t set = 0; set < sets; set++) {
        VkDescriptorSetLayoutBinding bindings[MAX_ITEMS];
        uint32_t used = 0;
        for (unsigned i = 0; i < count; i++) {
            if (descriptors[i].set != set) continue;
            bindings[used++] = (VkDescriptorSetLayoutBinding){
                .binding = descriptors[i].binding,
                .descriptorType = descriptors[i].type,
                .descriptorCount = 1,
                .stageFlags = VK_SHADER_STAGE_ALL,
            };
        }
        VkDescriptorSetLayoutCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
            .bindingCount = used,
            .pBindings = bindings};
        CHECK(create_set(device, &info, NULL, &set_layouts[set]), "vkCreateDescriptorSetLayout");
    }
    VkPushConstantRange push_constants = {.stageFlags = VK_SHADER_STAGE_ALL,
                                          .size = push_constant_bytes};
    VkPipelineLayoutCreateInfo info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                       .setLayoutCount = sets,
                                       .pSetLayouts = set_layouts,
                                       .pushConstantRangeCount = push_constant_bytes ? 1 : 0,
                                       .pPushConstantRanges = &push_constants};
    VkPipelineLayout layout;
    CHECK(create_layout(device, &info, NULL, &layout), "vkCreatePipelineLayout");
    return layout;
}

/* An attachment of `format`, loaded and stored, in the general layout throughout: the render
 * pass exists only for the pipeline to be created against. */
static VkAttachmentDescription attachment(VkFormat format) {
    return (VkAttachmentDescription){
        .format = format,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
        .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
        .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
        .initialLayout = VK_IMAGE_LAYOUT_GENERAL,
        .finalLayout = VK_IMAGE_LAYOUT_GENERAL,
    };
}

/* A render pass with one colour attachment a format, and the input attachments the shader
 * names (its input-attachment descriptors, in binding order) as extra attachments. */
static VkRenderPass render_pass(VkDevice device, const VkFormat *colors, unsigned color_count,
                                const struct descriptor *descriptors, unsigned descriptor_count) {
    VkAttachmentDescription attachments[2 * MAX_ITEMS];
    VkAttachmentReference color_references[MAX_ITEMS], input_references[MAX_ITEMS];
    unsigned attachment_count = 0, input_count = 0;
    for (unsigned i = 0; i < color_count; i++) {
        color_references[i] = (VkAttachmentReference){attachment_count,
                                                      VK_IMAGE_LAYOUT_GENERAL};
        attachments[attachment_count++] = attachment(colors[i]);
    }
    for (unsigned i = 0; i < descriptor_count; i++) {
        if (descriptors[i].type != VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT) continue;
        /* Input attachment index = binding order; the shader's index is the binding here. */
        input_references[input_count++] = (VkAttachmentReference){attachment_count,
                                                                  VK_IMAGE_LAYOUT_GENERAL};
        attachments[attachment_count++] = attachment(VK_FORMAT_R32_UINT);
    }
    VkSubpassDescription subpass = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                                    .inputAttachmentCount = input_count,
                                    .pInputAttachments = input_references,
                                    .colorAttachmentCount = color_count,
                                    .pColorAttachments = color_references};
    VkRenderPassCreateInfo info = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                   .attachmentCount = attachment_count,
                                   .pAttachments = attachments,
                                   .subpassCount = 1,
                                   .pSubpasses = &subpass};
    PFN_vkCreateRenderPass create =
        (PFN_vkCreateRenderPass)device_function(device, "vkCreateRenderPass");
    VkRenderPass pass;
    CHECK(create(device, &info, NULL, &pass), "vkCreateRenderPass");
    return pass;
}

/* What a graphics pipeline is made of, from one group of the command line. */
struct graphics {
    VkShaderModule vertex, fragment;
    const char *vertex_entry, *entry;
    VkPipelineLayout layout;
    const VkFormat *colors;
    unsigned color_count;
    /* Set 0's input-attachment descriptors, which under local read are the first colours. */
    unsigned input_count;
    const struct attribute_format *attributes;
    unsigned attribute_count;
    enum rendering rendering;
    /* The render pass (RENDER_PASS only). */
    VkRenderPass pass;
};

static VkPipeline graphics_pipeline(VkDevice device, const struct graphics *graphics,
                                    VkPipelineCreateFlags flags) {
    VkPipelineShaderStageCreateInfo stages[2] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .module = graphics->vertex,
         .pName = graphics->vertex_entry},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .module = graphics->fragment,
         .pName = graphics->entry},
    };
    VkVertexInputBindingDescription bindings[MAX_ITEMS];
    VkVertexInputAttributeDescription attributes[MAX_ITEMS];
    for (unsigned i = 0; i < graphics->attribute_count; i++) {
        bindings[i] = (VkVertexInputBindingDescription){
            .binding = i,
            .stride = graphics->attributes[i].bytes,
            .inputRate = VK_VERTEX_INPUT_RATE_VERTEX};
        attributes[i] = (VkVertexInputAttributeDescription){
            .location = i, .binding = i, .format = graphics->attributes[i].format};
    }
    VkPipelineVertexInputStateCreateInfo vertex_input = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = graphics->attribute_count,
        .pVertexBindingDescriptions = bindings,
        .vertexAttributeDescriptionCount = graphics->attribute_count,
        .pVertexAttributeDescriptions = attributes};
    VkPipelineInputAssemblyStateCreateInfo assembly = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkViewport viewport = {0, 0, 64, 64, 0, 1};
    VkRect2D scissor = {{0, 0}, {64, 64}};
    VkPipelineViewportStateCreateInfo viewport_state = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1,
        .pViewports = &viewport,
        .scissorCount = 1,
        .pScissors = &scissor};
    VkPipelineRasterizationStateCreateInfo raster = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .polygonMode = VK_POLYGON_MODE_FILL,
        .cullMode = VK_CULL_MODE_NONE,
        .lineWidth = 1};
    VkPipelineMultisampleStateCreateInfo multisample = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
    VkPipelineColorBlendAttachmentState blends[MAX_ITEMS];
    for (unsigned i = 0; i < graphics->color_count; i++)
        blends[i] = (VkPipelineColorBlendAttachmentState){.colorWriteMask = 0xf};
    VkPipelineColorBlendStateCreateInfo blend = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = graphics->color_count,
        .pAttachments = blends};
    /* Under local read: no render pass; each colour at its own location, input attachment
     * index i reading colour i. */
    uint32_t locations[MAX_ITEMS], input_indices[MAX_ITEMS];
    for (unsigned i = 0; i < graphics->color_count; i++) {
        locations[i] = i;
        input_indices[i] = i < graphics->input_count ? i : VK_ATTACHMENT_UNUSED;
    }
    VkRenderingInputAttachmentIndexInfoKHR input_info = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INPUT_ATTACHMENT_INDEX_INFO_KHR,
        .colorAttachmentCount = graphics->color_count,
        .pColorAttachmentInputIndices = input_indices};
    VkRenderingAttachmentLocationInfoKHR location_info = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_LOCATION_INFO_KHR,
        .pNext = &input_info,
        .colorAttachmentCount = graphics->color_count,
        .pColorAttachmentLocations = locations};
    VkPipelineRenderingCreateInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
        .pNext = &location_info,
        .colorAttachmentCount = graphics->color_count,
        .pColorAttachmentFormats = graphics->colors};
    if (graphics->rendering == LOCAL_READ_ORDERED)
        blend.flags = VK_PIPELINE_COLOR_BLEND_STATE_CREATE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_BIT_EXT;
    VkGraphicsPipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .pNext = graphics->rendering == RENDER_PASS ? NULL : &rendering,
        .flags = flags,
        .stageCount = 2,
        .pStages = stages,
        .pVertexInputState = &vertex_input,
        .pInputAssemblyState = &assembly,
        .pViewportState = &viewport_state,
        .pRasterizationState = &raster,
        .pMultisampleState = &multisample,
        .pColorBlendState = &blend,
        .layout = graphics->layout,
        .renderPass = graphics->pass};
    PFN_vkCreateGraphicsPipelines create =
        (PFN_vkCreateGraphicsPipelines)device_function(device, "vkCreateGraphicsPipelines");
    VkPipeline pipeline;
    CHECK(create(device, VK_NULL_HANDLE, 1, &info, NULL, &pipeline), "vkCreateGraphicsPipelines");
    return pipeline;
}

static VkPipeline compute_pipeline(VkDevice device, VkShaderModule module, const char *entry,
                                   VkPipelineLayout layout, VkPipelineCreateFlags flags) {
    VkComputePipelineCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = flags,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = module,
                  .pName = entry},
        .layout = layout};
    PFN_vkCreateComputePipelines create =
        (PFN_vkCreateComputePipelines)device_function(device, "vkCreateComputePipelines");
    VkPipeline pipeline;
    CHECK(create(device, VK_NULL_HANDLE, 1, &info, NULL, &pipeline), "vkCreateComputePipelines");
    return pipeline;
}

static void print_statistic(const VkPipelineExecutableStatisticKHR *statistic) {
    printf("statistic: %s = ", statistic->name);
    switch (statistic->format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
        printf("%u\n", statistic->value.b32);
        break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
        printf("%lld\n", (long long)statistic->value.i64);
        break;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
        printf("%llu\n", (unsigned long long)statistic->value.u64);
        break;
    default:
        printf("%.9g\n", statistic->value.f64);
        break;
    }
}

/* A zeroed array of `count` (at least one) Vulkan output structures of `size` bytes each, with
 * every sType set: the second call of Vulkan's count-then-fill idiom. Every such structure
 * begins with its sType. */
static void *vulkan_outputs(uint32_t count, size_t size, VkStructureType type) {
    char *array = calloc(count ? count : 1, size);
    if (!array) fail("out of memory");
    for (uint32_t i = 0; i < count; i++) memcpy(array + i * size, &type, sizeof type);
    return array;
}

static void print_executables(VkDevice device, VkPipeline pipeline, int disassembly) {
    PFN_vkGetPipelineExecutablePropertiesKHR properties =
        (PFN_vkGetPipelineExecutablePropertiesKHR)device_function(
            device, "vkGetPipelineExecutablePropertiesKHR");
    PFN_vkGetPipelineExecutableStatisticsKHR statistics =
        (PFN_vkGetPipelineExecutableStatisticsKHR)device_function(
            device, "vkGetPipelineExecutableStatisticsKHR");
    PFN_vkGetPipelineExecutableInternalRepresentationsKHR representations =
        (PFN_vkGetPipelineExecutableInternalRepresentationsKHR)device_function(
            device, "vkGetPipelineExecutableInternalRepresentationsKHR");
    VkPipelineInfoKHR pipeline_info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR,
                                       .pipeline = pipeline};
    uint32_t count = 0;
    CHECK(properties(device, &pipeline_info, &count, NULL), "vkGetPipelineExecutableProperties");
    VkPipelineExecutablePropertiesKHR *executables =
        vulkan_outputs(count, sizeof *executables,
                       VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR);
    CHECK(properties(device, &pipeline_info, &count, executables),
          "vkGetPipelineExecutableProperties");
    for (uint32_t i = 0; i < count; i++) {
        printf("executable: %s\n", executables[i].name);
        VkPipelineExecutableInfoKHR info = {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR,
                                            .pipeline = pipeline,
                                            .executableIndex = i};
        uint32_t statistic_count = 0;
        CHECK(statistics(device, &info, &statistic_count, NULL),
              "vkGetPipelineExecutableStatistics");
        VkPipelineExecutableStatisticKHR *values = vulkan_outputs(
            statistic_count, sizeof *values, VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR);
        CHECK(statistics(device, &info, &statistic_count, values),
              "vkGetPipelineExecutableStatistics");
        for (uint32_t s = 0; s < statistic_count; s++) print_statistic(&values[s]);
        free(values);
        if (!disassembly) continue;
        uint32_t text_count = 0;
        CHECK(representations(device, &info, &text_count, NULL),
              "vkGetPipelineExecutableInternalRepresentations");
        VkPipelineExecutableInternalRepresentationKHR *texts =
            vulkan_outputs(text_count, sizeof *texts,
                           VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INTERNAL_REPRESENTATION_KHR);
        CHECK(representations(device, &info, &text_count, texts),
              "vkGetPipelineExecutableInternalRepresentations");
        for (uint32_t t = 0; t < text_count; t++) {
            if (!texts[t].isText) continue;
            texts[t].pData = calloc(texts[t].dataSize + 1, 1);
        }
        CHECK(representations(device, &info, &text_count, texts),
              "vkGetPipelineExecutableInternalRepresentations");
        for (uint32_t t = 0; t < text_count; t++) {
            if (texts[t].isText)
                printf("representation: %s\n%s\nend-representation\n", texts[t].name,
                       (const char *)texts[t].pData);
            free(texts[t].pData);
        }
        free(texts);
    }
    free(executables);
}

/* What the device was opened with: a mode's pipelines are refused where it lacks what they
 * need, by these reasons (NULL: offered). */
static const char *local_read_missing = "no pipeline asked for local read";
static const char *rasterization_order_missing = "no pipeline asked for rasterization order";

/* One pipeline: STAGE SHADER.spv [VERTEX.spv] and its options. */
static void vulkan_pipeline(void *context, int argc, char **argv) {
    VkDevice device = context;
    if (argc < 2) usage();
    const char *stage = argv[0], *shader = argv[1], *vertex = NULL, *entry = "main";
    const char *vertex_entry = "main";
    struct descriptor descriptors[MAX_ITEMS];
    VkFormat colors[MAX_ITEMS];
    struct attribute_format attributes[MAX_ITEMS];
    unsigned descriptor_count = 0, color_count = 0, attribute_count = 0, push_constant_bytes = 0;
    enum rendering rendering = RENDER_PASS;
    int disassembly = 0;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--disassembly")) {
            disassembly = 1;
        } else if (!strcmp(argv[i], "--entry") && i + 1 < argc) {
            entry = argv[++i];
        } else if (!strcmp(argv[i], "--vertex-entry") && i + 1 < argc) {
            vertex_entry = argv[++i];
        } else if (!strcmp(argv[i], "--descriptor") && i + 1 < argc) {
            char kind[32];
            unsigned set, binding;
            if (descriptor_count == MAX_ITEMS ||
                sscanf(argv[++i], "%u,%u,%31s", &set, &binding, kind) != 3)
                usage();
            descriptors[descriptor_count++] =
                (struct descriptor){set, binding,
                                    (VkDescriptorType)named_value(descriptor_kinds, kind)};
        } else if (!strcmp(argv[i], "--color") && i + 1 < argc) {
            if (color_count == MAX_ITEMS) usage();
            colors[color_count++] = (VkFormat)named_value(color_formats, argv[++i]);
        } else if (!strcmp(argv[i], "--attribute") && i + 1 < argc) {
            if (attribute_count == MAX_ITEMS) usage();
            attributes[attribute_count++] = attribute_format(argv[++i]);
        } else if (!strcmp(argv[i], "--push-constants") && i + 1 < argc) {
            if (sscanf(argv[++i], "%u", &push_constant_bytes) != 1) usage();
        } else if (!strcmp(argv[i], "--rendering") && i + 1 < argc) {
            rendering = (enum rendering)named_value(renderings, argv[++i]);
        } else if (argv[i][0] != '-' && !vertex) {
            vertex = argv[i];
        } else {
            usage();
        }
    }
    int compute = !strcmp(stage, "compute");
    if (!compute && strcmp(stage, "fragment")) fail("Vulkan statistics are for fragment or compute");
    if (!compute && !vertex) fail("a fragment shader needs a vertex shader");
    if (rendering != RENDER_PASS && local_read_missing)
        fail("local read is not offered: %s", local_read_missing);
    if (rendering == LOCAL_READ_ORDERED && rasterization_order_missing)
        fail("rasterization-order attachment access is not offered: %s",
             rasterization_order_missing);

    VkPipelineCreateFlags flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    if (disassembly) flags |= VK_PIPELINE_CREATE_CAPTURE_INTERNAL_REPRESENTATIONS_BIT_KHR;
    VkPipelineLayout layout =
        pipeline_layout(device, descriptors, descriptor_count, push_constant_bytes);
    VkPipeline pipeline;
    if (compute) {
        pipeline = compute_pipeline(device, shader_module(device, shader), entry, layout, flags);
    } else {
        unsigned input_count = 0;
        for (unsigned i = 0; i < descriptor_count; i++)
            input_count += descriptors[i].type == VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
        if (rendering != RENDER_PASS && input_count > color_count)
            fail("%u input attachments but %u colours: under local read each input is a colour",
                 input_count, color_count);
        struct graphics graphics = {
            .vertex = shader_module(device, vertex),
            .fragment = shader_module(device, shader),
            .vertex_entry = vertex_entry,
            .entry = entry,
            .layout = layout,
            .colors = colors,
            .color_count = color_count,
            .input_count = input_count,
            .attributes = attributes,
            .attribute_count = attribute_count,
            .rendering = rendering,
            .pass = rendering == RENDER_PASS
                        ? render_pass(device, colors, color_count, descriptors, descriptor_count)
                        : VK_NULL_HANDLE,
        };
        pipeline = graphics_pipeline(device, &graphics, flags);
    }
    print_executables(device, pipeline, disassembly);
}

/* Whether any group of the command line asks for `mode` (or, for local read, its ordered
 * form): the device is opened with what those pipelines need only when one does. */
static int asks_for(int argc, char **argv, const char *mode) {
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--rendering") && !strncmp(argv[i + 1], mode, strlen(mode)))
            return 1;
    return 0;
}

/* Whether the device offers extension `name`. */
static int offers_extension(VkInstance instance, VkPhysicalDevice physical, const char *name) {
    PFN_vkEnumerateDeviceExtensionProperties enumerate =
        (PFN_vkEnumerateDeviceExtensionProperties)instance_function(
            instance, "vkEnumerateDeviceExtensionProperties");
    uint32_t count = 0;
    if (!enumerate || enumerate(physical, NULL, &count, NULL) != VK_SUCCESS) return 0;
    VkExtensionProperties *extensions = calloc(count ? count : 1, sizeof *extensions);
    int found = 0;
    if (extensions && enumerate(physical, NULL, &count, extensions) == VK_SUCCESS)
        for (uint32_t i = 0; i < count && !found; i++)
            found = !strcmp(extensions[i].extensionName, name);
    free(extensions);
    return found;
}

static int run_vulkan(int argc, char **argv) {
    if (argc < 2) usage();
    int local_read = asks_for(argc, argv, "local-read");
    int rasterization_order = asks_for(argc, argv, "local-read-ordered");
    void *loader = library("libvulkan.so.1");
    instance_function = (PFN_vkGetInstanceProcAddr)dlsym(loader, "vkGetInstanceProcAddr");
    if (!instance_function) fail("libvulkan.so.1 has no vkGetInstanceProcAddr");
    PFN_vkCreateInstance create_instance =
        (PFN_vkCreateInstance)instance_function(NULL, "vkCreateInstance");
    VkApplicationInfo application = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                                     .pApplicationName = "shader-stats",
                                     /* Dynamic rendering is core in 1.3. */
                                     .apiVersion = local_read ? VK_API_VERSION_1_3
                                                              : VK_API_VERSION_1_1};
    VkInstanceCreateInfo instance_info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                          .pApplicationInfo = &application};
    VkInstance instance;
    CHECK(create_instance(&instance_info, NULL, &instance), "vkCreateInstance");
    PFN_vkEnumeratePhysicalDevices enumerate =
        (PFN_vkEnumeratePhysicalDevices)instance_function(instance, "vkEnumeratePhysicalDevices");
    PFN_vkGetPhysicalDeviceProperties2 properties2 =
        (PFN_vkGetPhysicalDeviceProperties2)instance_function(instance,
                                                              "vkGetPhysicalDeviceProperties2");
    PFN_vkCreateDevice create_device =
        (PFN_vkCreateDevice)instance_function(instance, "vkCreateDevice");
    device_function =
        (PFN_vkGetDeviceProcAddr)instance_function(instance, "vkGetDeviceProcAddr");
    uint32_t count = 1;
    VkPhysicalDevice physical;
    VkResult found = enumerate(instance, &count, &physical);
    if ((found != VK_SUCCESS && found != VK_INCOMPLETE) || count == 0)
        fail("no Vulkan device");
    VkPhysicalDeviceDriverProperties driver = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
    properties2(physical, &properties);
    printf("device: %s\n", properties.properties.deviceName);
    printf("driver: %s %s\n", driver.driverName, driver.driverInfo);
    fflush(stdout);

    float priority = 1;
    VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                     .queueFamilyIndex = 0,
                                     .queueCount = 1,
                                     .pQueuePriorities = &priority};
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable_feature = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
        .pipelineExecutableInfo = VK_TRUE};
    const char *extensions[4] = {VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME};
    uint32_t extension_count = 1;
    /* Local read, where a pipeline asks for it: dynamic rendering (core in 1.3), its local
     * read, and rasterization order (EXT's, or ARM's it was promoted from), each enabled only
     * where the device offers it; what is not offered is named to the pipelines that ask. */
    VkPhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT order_feature = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_FEATURES_EXT};
    VkPhysicalDeviceDynamicRenderingLocalReadFeaturesKHR local_read_feature = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_LOCAL_READ_FEATURES_KHR};
    VkPhysicalDeviceDynamicRenderingFeatures dynamic_rendering_feature = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    if (local_read) {
        const char *order_extension =
            offers_extension(instance, physical, "VK_EXT_rasterization_order_attachment_access")
                ? "VK_EXT_rasterization_order_attachment_access"
            : offers_extension(instance, physical, "VK_ARM_rasterization_order_attachment_access")
                ? "VK_ARM_rasterization_order_attachment_access"
                : NULL;
        int offers_local_read =
            offers_extension(instance, physical, VK_KHR_DYNAMIC_RENDERING_LOCAL_READ_EXTENSION_NAME);
        /* What the device offers: the features of the extensions it has. */
        dynamic_rendering_feature.pNext = offers_local_read ? &local_read_feature : NULL;
        local_read_feature.pNext = order_extension ? &order_feature : NULL;
        VkPhysicalDeviceFeatures2 features = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                              .pNext = &dynamic_rendering_feature};
        int vulkan_1_3 = properties.properties.apiVersion >= VK_API_VERSION_1_3;
        if (vulkan_1_3)
            ((PFN_vkGetPhysicalDeviceFeatures2)instance_function(
                instance, "vkGetPhysicalDeviceFeatures2"))(physical, &features);
        if (!vulkan_1_3)
            local_read_missing = "the device's Vulkan is older than 1.3 (dynamic rendering)";
        else if (!offers_local_read)
            local_read_missing = "the device lacks " VK_KHR_DYNAMIC_RENDERING_LOCAL_READ_EXTENSION_NAME;
        else if (!dynamic_rendering_feature.dynamicRendering)
            local_read_missing = "the device lacks the dynamicRendering feature";
        else if (!local_read_feature.dynamicRenderingLocalRead)
            local_read_missing = "the device lacks the dynamicRenderingLocalRead feature";
        else
            local_read_missing = NULL;
        if (!order_extension)
            rasterization_order_missing =
                "the device lacks VK_EXT_rasterization_order_attachment_access (and ARM's)";
        else if (!order_feature.rasterizationOrderColorAttachmentAccess)
            rasterization_order_missing =
                "the device lacks the rasterizationOrderColorAttachmentAccess feature";
        else
            rasterization_order_missing = NULL;
        /* What is enabled: only what some pipeline asked for and the device offers. */
        dynamic_rendering_feature.pNext = NULL;
        local_read_feature.pNext = NULL;
        if (!local_read_missing) {
            extensions[extension_count++] = VK_KHR_DYNAMIC_RENDERING_LOCAL_READ_EXTENSION_NAME;
            executable_feature.pNext = &dynamic_rendering_feature;
            dynamic_rendering_feature.pNext = &local_read_feature;
        }
        if (!local_read_missing && rasterization_order && !rasterization_order_missing) {
            extensions[extension_count++] = order_extension;
            local_read_feature.pNext = &order_feature;
            order_feature = (VkPhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT){
                .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_FEATURES_EXT,
                .rasterizationOrderColorAttachmentAccess = VK_TRUE};
        }
    }
    VkDeviceCreateInfo device_info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                      .pNext = &executable_feature,
                                      .queueCreateInfoCount = 1,
                                      .pQueueCreateInfos = &queue,
                                      .enabledExtensionCount = extension_count,
                                      .ppEnabledExtensionNames = extensions};
    VkDevice device;
    CHECK(create_device(physical, &device_info, NULL, &device),
          "vkCreateDevice with VK_KHR_pipeline_executable_properties");

    each_shader(argc, argv, vulkan_pipeline, device);
    return 0;
}

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (argc < 2) usage();
    if (!strcmp(argv[1], "gl")) return run_gl(argc - 2, argv + 2);
    if (!strcmp(argv[1], "vulkan")) return run_vulkan(argc - 2, argv + 2);
    usage();
    return 2;
}
